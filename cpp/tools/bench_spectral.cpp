// Cost of the spectral basis (native): the eigen-decomposition (-L phi = lambda M phi, shift-invert Lanczos on
// a sparse Cholesky factor) and the orthonormalisation of B = [1, x0, y0, z0, phi_1 .. phi_k], on the capsules of
// the solver benchmark (length 4, radius 0.5; bench_case.h) at n = 5k, 20k, 50k with k = 50, 100, 200 by
// default, and optionally on mesh files. Prints one JSON line per case: wall and CPU ms (the machine may be
// shared), the factorization's share, Lanczos solves and restarts, and the memory the refusal rule counts.
//   build/native/bench_spectral [--sizes 5000,20000,50000] [--modes 50,100,200] [file.obj ...]
#include <cstdio>
#include <cstring>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/mesh/mesh_io.h"
#include "core/timer.h"
#include "core/basis/spectral_basis.h"
#include "tools/bench_case.h"
#include "tools/read_mesh_file.h"

namespace {

using sd::now_ms;

double cpu_ms() { return 1e3 * double(std::clock()) / CLOCKS_PER_SEC; }

std::vector<int> parse_list(const char* text) {
  std::vector<int> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stoi(item));
  return out;
}

void run(const std::string& name, const sd::Mesh& mesh, int modes) {
  sd::SpectralOptions options;
  options.modes = modes;
  options.memory_budget_bytes = std::size_t(4) << 30;
  const double t0 = now_ms(), c0 = cpu_ms();
  const sd::SpectralBasis basis = sd::spectral_basis(mesh, options);
  const double wall = now_ms() - t0, cpu = cpu_ms() - c0;
  std::printf(
      "{\"mesh\": \"%s\", \"n\": %d, \"modes\": %d, \"ms\": %.0f, \"cpuMs\": %.0f, \"eigenMs\": %.0f, "
      "\"orthonormalizeMs\": %.0f, \"solves\": %d, \"columns\": %d, \"dropped\": %d, \"memoryMB\": %.0f}\n",
      name.c_str(), static_cast<int>(mesh.V.rows()), modes, wall, cpu, basis.eigen_ms, basis.orthonormalize_ms,
      basis.operations, basis.B.cols(), basis.dropped,
      sd::spectral_basis_memory_bytes(static_cast<int>(mesh.V.rows()), modes) / 1e6);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{5000, 20000, 50000}, modes{50, 100, 200};
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) sizes = parse_list(argv[++i]);
    else if (!std::strcmp(argv[i], "--modes") && i + 1 < argc) modes = parse_list(argv[++i]);
    else files.push_back(argv[i]);
  }
  try {
    for (int n : sizes)
      for (int k : modes) run("capsule", sd::bench::capsule(n), k);
    for (const std::string& path : files)
      for (int k : modes) run(path.substr(path.find_last_of('/') + 1), sd::tools::read_mesh_file(path), k);
  } catch (const sd::Error& e) {
    std::fprintf(stderr, "bench_spectral: %s\n", e.what());
    return 1;
  }
}
