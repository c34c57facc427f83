// libFuzzer target for automatic cage generation (built and run by scripts/fuzz.sh).
// Random bytes rarely form a closed mesh, so the input is read as a recipe instead: a base shape (box,
// icosphere or capsule, small), then edits a user's file can carry (moved or collapsed vertices, NaN,
// extreme scales, flipped, removed or duplicated faces), then the options (K, offset, resolution,
// including absurd values). generate_cage must either return a cage that passes its own independent
// check (cage_defect) or throw sd::Error; any other exception, a crash or a sanitizer report is a finding.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "core/cage/cage_generation.h"
#include "core/error.h"
#include "core/mesh/shapes.h"

namespace {

// Reads the fuzzer's bytes as small numbers, then zeros once they run out.
class Recipe {
 public:
  Recipe(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  int byte() { return at_ < size_ ? data_[at_++] : 0; }
  int pick(int n) { return byte() % n; }
  // A scale from 1e-300 to 1e300 (mostly near 1), or NaN / inf.
  double scale() {
    switch (pick(8)) {
      case 0: return std::pow(10.0, (byte() - 128) * 300.0 / 128.0);
      case 1: return std::numeric_limits<double>::quiet_NaN();
      case 2: return std::numeric_limits<double>::infinity();
      case 3: return -1.0;
      default: return 0.5 + byte() / 128.0;
    }
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t at_ = 0;
};

sd::Mesh base_shape(Recipe& r) {
  switch (r.pick(3)) {
    case 0: return sd::make_box(1 + r.pick(3), 1, 0.5 + r.pick(4) * 0.25, 1 + r.pick(3));
    case 1: return sd::make_icosphere(r.pick(3), 1.0);
    default: return sd::make_capsule(1 + r.pick(3), 0.3, 2 + r.pick(3), 1 + r.pick(3), 6 + r.pick(6));
  }
}

void edit(sd::Mesh& mesh, Recipe& r) {
  const int edits = r.pick(6);
  for (int e = 0; e < edits; ++e) {
    const int v = r.pick(static_cast<int>(mesh.V.rows()));
    const int f = r.pick(static_cast<int>(mesh.F.rows()));
    switch (r.pick(7)) {
      case 0: mesh.V.row(v) *= r.scale(); break;                            // move a vertex far or to NaN
      case 1: mesh.V.row(v) = mesh.V.row(mesh.F(f, 0)); break;              // collapse onto another
      case 2: mesh.V *= r.scale(); break;                                   // rescale everything
      case 3: std::swap(mesh.F(f, 1), mesh.F(f, 2)); break;                 // flip a face
      case 4: mesh.F.row(f) = mesh.F.row((f + 1) % mesh.F.rows()); break;   // duplicate a face
      case 5: mesh.F(f, r.pick(3)) = r.pick(3) == 0 ? -1 : 1 << 20; break;  // index out of range
      default: mesh.V.col(r.pick(3)) *= 1e-14; break;                       // flatten
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Recipe r(data, size);
  sd::Mesh mesh = base_shape(r);
  edit(mesh, r);
  sd::CageOptions options;
  // Small targets and grids keep one execution well under a second.
  options.target_vertices = r.pick(4) == 0 ? r.byte() * 1000 - 3 : 4 + r.pick(40);
  options.offset = r.pick(3) == 0 ? r.scale() : 0.0;
  options.resolution = r.pick(4) == 0 ? 8 + r.pick(40) : r.pick(2) == 0 ? 0 : r.byte() * 100;
  options.max_attempts = 1 + r.pick(2);
  try {
    const sd::CageResult result = sd::generate_cage(mesh, options);
    const double diagonal = sd::bounding_box_diagonal(mesh.V);
    if (!sd::cage_defect(mesh, result.cage, 1e-9 * diagonal).empty()) std::abort();  // returned an invalid cage
  } catch (const sd::Error&) {
    // a named refusal is the expected outcome for broken recipes
  }
  return 0;
}
