#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <system_error>

#include "io/io_error.h"

namespace svgf::io {

void write_atomically(const std::string& path,
                      const std::function<void(const std::string&)>& write) {
  // pid + counter: unique across processes and across threads of this one.
  static std::atomic<unsigned long> counter{0};
  const std::string tmp = path + ".tmp-" + std::to_string(static_cast<long>(::getpid())) + "-" +
                          std::to_string(counter.fetch_add(1));
  try {
    write(tmp);
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw IoError(path + ": cannot rename temporary file into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

}  // namespace svgf::io
