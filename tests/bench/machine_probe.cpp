// rkmachine: what one core of this machine can do, for the bench's machine-limit estimate.
// Measures the memory bandwidth (STREAM triad a = b + s c, 24 bytes per element as STREAM counts
// them) for working sets from cache-sized to DRAM-sized, and the peak double-precision rate of
// independent multiply-add chains, both as this build compiles them (the project's flags: the
// machine's vector units with RK_NATIVE, else SSE2; GCC contracts x * m + c to FMA where the target
// has it) and with AVX-512 FMA where the CPU has it (the core's peak). Prints one JSON object.
//   rkmachine [--seconds S]   (each measurement repeats for about S seconds, best rate kept)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// best of repeated runs of `fn` (which returns the work it did) over about `seconds`
template <class Fn>
double best_rate(double seconds, Fn fn) {
  double best = 0;
  const double end = now() + seconds;
  do {
    const double t0 = now();
    const double work = fn();
    const double t = now() - t0;
    if (t > 0 && work / t > best) best = work / t;
  } while (now() < end);
  return best;
}

double triad_bytes_per_s(std::size_t bytes, double seconds) {
  const std::size_t n = bytes / 24;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 1.0000001;
  return best_rate(seconds, [&] {
    const int reps = int(std::max<std::size_t>(1, (std::size_t(64) << 20) / bytes));
    for (int r = 0; r < reps; ++r) {
      double* __restrict pa = a.data();
      const double* __restrict pb = b.data();
      const double* __restrict pc = c.data();
      for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
      b[r % n] = a[(r * 7) % n];  // keeps the loop from being hoisted
    }
    return 24.0 * double(n) * reps;
  });
}

// Independent chains x = x * m + c, enough to cover the latency of the vector units (the compiler
// vectorizes them with what the target allows): 32 in 16 SSE2 registers, 64 in 16 AVX registers
// or 8 AVX-512 registers (two pipes of latency 4).
constexpr int kMaxChains = 64;
constexpr long kIterations = 1'000'000;
#if defined(__AVX512F__)
constexpr int kBuildChains = 64, kBuildVectorBits = 512;
#elif defined(__AVX__)
constexpr int kBuildChains = 64, kBuildVectorBits = 256;
#else
constexpr int kBuildChains = 32, kBuildVectorBits = 128;
#endif

double chains_build(double* x, double m, double c) {
  for (long it = 0; it < kIterations; ++it)
    for (int k = 0; k < kBuildChains; ++k) x[k] = x[k] * m + c;
  return 2.0 * kBuildChains * double(kIterations);
}

__attribute__((target("avx512f,fma"))) double chains_avx512(double* x, double m, double c) {
  for (long it = 0; it < kIterations; ++it)
    for (int k = 0; k < 64; ++k) x[k] = __builtin_fma(x[k], m, c);
  return 2.0 * 64 * double(kIterations);
}

template <class Kernel>
double flops_per_s(double seconds, Kernel kernel) {
  alignas(64) double x[kMaxChains];
  for (int k = 0; k < kMaxChains; ++k) x[k] = 1.0 + 1e-3 * k;
  const double rate = best_rate(seconds, [&] { return kernel(x, 0.999999, 1e-7); });
  double sum = 0;
  for (double v : x) sum += v;
  if (sum == 42.0) std::printf(" ");  // uses the result
  return rate;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 0.5;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr, "rkmachine: unknown argument '%s' (usage: rkmachine [--seconds S])\n", argv[i]);
      return 2;
    }
  }
  std::printf("{\n  \"triad_gb_per_s\": {");
  const std::size_t sizes_kib[] = {256, 4096, 16384, 1048576};  // L2, L3, L3, DRAM working sets
  for (std::size_t i = 0; i < 4; ++i)
    std::printf("%s\"%zu_kib\": %.2f", i ? ", " : "", sizes_kib[i], 1e-9 * triad_bytes_per_s(sizes_kib[i] << 10, seconds));
  std::printf("},\n  \"build_vector_bits\": %d", kBuildVectorBits);
  std::printf(",\n  \"gflop_per_s_this_build\": %.2f", 1e-9 * flops_per_s(seconds, chains_build));
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("fma"))
    std::printf(",\n  \"gflop_per_s_avx512_fma\": %.2f", 1e-9 * flops_per_s(seconds, chains_avx512));
  std::printf("\n}\n");
  return 0;
}
