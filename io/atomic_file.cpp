#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
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

void write_file_atomically(const std::string& path, const std::string& bytes) {
  write_atomically(path, [&](const std::string& tmp) {
    // stdio rather than a stream: its calls report errno (EFBIG, ENOSPC) for the message.
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw IoError(path + ": cannot open for writing: " + std::strerror(errno));
    const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
    const int write_errno = errno;
    if (written != bytes.size()) {
      std::fclose(f);
      throw IoError(path + ": write error: " + std::strerror(write_errno));
    }
    if (std::fclose(f) != 0) throw IoError(path + ": write error: " + std::strerror(errno));
  });
}

}  // namespace svgf::io
