// Device identity and measured ceilings (bench/gpu_probe.h). The ceilings are what the floor
// analysis divides by, so they are measured here rather than taken from a datasheet.
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/gpu_probe.h"

namespace svgf::bench {
namespace {

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw std::runtime_error(std::string("svgf-bench: ") + what + ": " + cudaGetErrorName(e) +
                             ": " + cudaGetErrorString(e));
}

// Eight independent FMA chains per thread, so the pipelines stay full.
constexpr int kChains = 8;
__global__ void fma_kernel(float* out, int iterations, float b, float c) {
  float a[kChains];
#pragma unroll
  for (int k = 0; k < kChains; ++k) a[k] = static_cast<float>(threadIdx.x + k);
  for (int i = 0; i < iterations; ++i) {
#pragma unroll
    for (int k = 0; k < kChains; ++k) a[k] = __fmaf_rn(a[k], b, c);
  }
  float s = 0.f;
#pragma unroll
  for (int k = 0; k < kChains; ++k) s += a[k];
  if (s == 1.2345f) out[blockIdx.x] = s;  // never true in practice; keeps the work alive
}

__global__ void copy_kernel(const float4* __restrict__ in, float4* __restrict__ out, size_t n) {
  const size_t stride = static_cast<size_t>(gridDim.x) * blockDim.x;
  for (size_t i = static_cast<size_t>(blockIdx.x) * blockDim.x + threadIdx.x; i < n; i += stride)
    out[i] = in[i];
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Times `work` (enqueued on `stream`) `reps` times with events, after one warm-up; median ms.
template <class Work>
double time_ms(cudaStream_t stream, int reps, const Work& work) {
  cudaEvent_t start, stop;
  check(cudaEventCreate(&start), "cudaEventCreate");
  check(cudaEventCreate(&stop), "cudaEventCreate");
  work();
  check(cudaStreamSynchronize(stream), "warm-up");
  std::vector<double> ms;
  for (int r = 0; r < reps; ++r) {
    check(cudaEventRecord(start, stream), "cudaEventRecord");
    work();
    check(cudaEventRecord(stop, stream), "cudaEventRecord");
    check(cudaEventSynchronize(stop), "cudaEventSynchronize");
    float t = 0.f;
    check(cudaEventElapsedTime(&t, start, stop), "cudaEventElapsedTime");
    ms.push_back(t);
  }
  cudaEventDestroy(start);
  cudaEventDestroy(stop);
  return median(ms);
}

}  // namespace

DeviceInfo query_device() {
  DeviceInfo d;
  int count = 0;
  cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess || count == 0) {
    (void)cudaGetLastError();
    d.why_absent = e != cudaSuccess ? std::string(cudaGetErrorString(e)) : "no CUDA device";
    return d;
  }
  int dev = 0;
  check(cudaGetDevice(&dev), "cudaGetDevice");
  cudaDeviceProp prop{};
  check(cudaGetDeviceProperties(&prop, dev), "cudaGetDeviceProperties");
  d.present = true;
  d.name = prop.name;
  d.compute_major = prop.major;
  d.compute_minor = prop.minor;
  d.sms = prop.multiProcessorCount;
  d.memory_bytes = prop.totalGlobalMem;
  check(cudaDriverGetVersion(&d.driver_version), "cudaDriverGetVersion");
  check(cudaRuntimeGetVersion(&d.runtime_version), "cudaRuntimeGetVersion");
  check(cudaDeviceGetAttribute(&d.clock_khz, cudaDevAttrClockRate, dev), "clock rate");
  check(cudaDeviceGetAttribute(&d.memory_clock_khz, cudaDevAttrMemoryClockRate, dev),
        "memory clock rate");
  check(cudaDeviceGetAttribute(&d.memory_bus_bits, cudaDevAttrGlobalMemoryBusWidth, dev),
        "memory bus width");
  check(cudaDeviceGetAttribute(&d.l2_bytes, cudaDevAttrL2CacheSize, dev), "L2 size");
  return d;
}

void measure_ceilings(DeviceInfo& info) {
  if (!info.present) return;
  cudaStream_t stream;
  check(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking), "cudaStreamCreate");

  // Copies of 1 GiB: far past the L2, so DRAM is what is measured. Bytes = read + write.
  const size_t bytes = size_t(1) << 30;
  void* a = nullptr;
  void* b = nullptr;
  check(cudaMalloc(&a, bytes), "cudaMalloc for the copy test");
  check(cudaMalloc(&b, bytes), "cudaMalloc for the copy test");
  check(cudaMemsetAsync(a, 1, bytes, stream), "cudaMemset");  // not zeros: real data
  const double memcpy_ms = time_ms(stream, 10, [&] {
    check(cudaMemcpyAsync(b, a, bytes, cudaMemcpyDeviceToDevice, stream), "cudaMemcpyAsync");
  });
  info.memcpy_gbs = 2.0 * static_cast<double>(bytes) / (memcpy_ms * 1e-3) / 1e9;
  const size_t n4 = bytes / sizeof(float4);
  const int copy_blocks = info.sms * 8;
  const double kernel_ms = time_ms(stream, 10, [&] {
    copy_kernel<<<copy_blocks, 512, 0, stream>>>(static_cast<const float4*>(a),
                                                 static_cast<float4*>(b), n4);
    check(cudaGetLastError(), "copy kernel launch");
  });
  info.copy_kernel_gbs = 2.0 * static_cast<double>(bytes) / (kernel_ms * 1e-3) / 1e9;
  check(cudaFree(a), "cudaFree");
  check(cudaFree(b), "cudaFree");

  // FP32 rate: enough blocks for every SM several times over.
  float* sink = nullptr;
  const int blocks = info.sms * 16, threads = 256, iterations = 8192;
  check(cudaMalloc(&sink, blocks * sizeof(float)), "cudaMalloc for the FMA test");
  const double fma_ms = time_ms(stream, 5, [&] {
    fma_kernel<<<blocks, threads, 0, stream>>>(sink, iterations, 0.999f, 0.001f);
    check(cudaGetLastError(), "FMA kernel launch");
  });
  const double instructions = static_cast<double>(blocks) * threads * iterations * kChains;
  info.fp32_ops_per_s = instructions / (fma_ms * 1e-3);
  check(cudaFree(sink), "cudaFree");
  check(cudaStreamDestroy(stream), "cudaStreamDestroy");
}

size_t device_used_bytes() {
  size_t free_bytes = 0, total = 0;
  if (cudaMemGetInfo(&free_bytes, &total) != cudaSuccess) {
    (void)cudaGetLastError();
    return 0;
  }
  return total - free_bytes;
}

namespace {

// One frame's channels in device memory, planar (the frame's own layout), and its views.
class DeviceCopy {
 public:
  explicit DeviceCopy(const Frame& f) : frame_(f.width(), f.height()) {
    frame_.index = f.index;
    frame_.camera = f.camera;
    frame_.color = put(f.color.data(), f.color);
    frame_.albedo = put(f.albedo.data(), f.albedo);
    frame_.normal = put(f.normal.data(), f.normal);
    frame_.depth = put(f.depth.data(), f.depth);
    frame_.depth_gradient = put(f.depth_gradient.data(), f.depth_gradient);
    frame_.motion = put(f.motion.data(), f.motion);
    std::vector<float> ids(f.mesh_id.size());
    std::memcpy(ids.data(), f.mesh_id.data(), ids.size() * sizeof(float));
    frame_.mesh_id = put(ids, f.depth);
    if (!f.emission.empty()) frame_.emission = put(f.emission.data(), f.emission);
    if (!f.position.empty()) frame_.position = put(f.position.data(), f.position);
    if (!f.direct.empty()) frame_.direct = put(f.direct.data(), f.direct);
    if (!f.indirect.empty()) frame_.indirect = put(f.indirect.data(), f.indirect);
    // The host path reads the mask to see whether the frame has samples; a device frame
    // says so by its view (core/device_frame.h).
    bool samples = false;
    if (!f.gradient.empty())
      for (size_t i = 0; i < f.gradient.pixel_count() && !samples; ++i)
        samples = f.gradient.plane(2)[i] > 0.5f;
    if (samples) frame_.gradient = put(f.gradient.data(), f.gradient);
  }
  ~DeviceCopy() {
    for (void* p : buffers_) cudaFree(p);
  }
  DeviceCopy(const DeviceCopy&) = delete;
  DeviceCopy& operator=(const DeviceCopy&) = delete;
  const DeviceFrame& frame() const { return frame_; }

 private:
  DeviceImageView put(const std::vector<float>& values, const Image& shape) {
    void* p = nullptr;
    check(cudaMalloc(&p, values.size() * sizeof(float)), "cudaMalloc of a device-path frame");
    buffers_.push_back(p);
    check(cudaMemcpy(p, values.data(), values.size() * sizeof(float), cudaMemcpyHostToDevice),
          "upload of a device-path frame");
    return DeviceImageView::planar(p, shape.width(), shape.height());
  }

  DeviceFrame frame_;
  std::vector<void*> buffers_;
};

double ms_between(std::chrono::steady_clock::time_point a,
                  std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

DevicePathTimes time_device_path(Denoiser& denoiser, const std::vector<Frame>& frames, int warmup,
                                 int count, const std::function<void(int, int)>& before) {
  DevicePathTimes t;
  if (frames.empty()) return t;
  std::vector<std::unique_ptr<DeviceCopy>> copies;
  for (const Frame& f : frames) copies.push_back(std::make_unique<DeviceCopy>(f));
  const int w = frames.front().width(), h = frames.front().height();
  void* out = nullptr;
  check(cudaMalloc(&out, 3 * sizeof(float) * w * h), "cudaMalloc of the device-path output");
  cudaStream_t stream = nullptr;
  check(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking), "cudaStreamCreate");
  const DeviceOutputView view = DeviceOutputView::planar(out, w, h);
  const int n = static_cast<int>(frames.size());
  for (int m = 0; m < warmup + count; ++m) {
    const int k = m % n;
    before(m, k);
    const auto t0 = std::chrono::steady_clock::now();
    denoiser.denoise_device(copies[static_cast<size_t>(k)]->frame(), view, stream);
    const auto t1 = std::chrono::steady_clock::now();
    check(cudaStreamSynchronize(stream), "cudaStreamSynchronize after a device-path frame");
    const auto t2 = std::chrono::steady_clock::now();
    if (m < warmup) continue;
    t.call_ms.push_back(ms_between(t0, t1));
    t.done_ms.push_back(ms_between(t0, t2));
  }
  (void)denoiser.last_report();  // raises any fault of the last frame
  check(cudaStreamDestroy(stream), "cudaStreamDestroy");
  check(cudaFree(out), "cudaFree");
  return t;
}

}  // namespace svgf::bench
