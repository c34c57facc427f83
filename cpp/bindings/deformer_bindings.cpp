// The Deformer session for JS (class DeformerSession). Wrapped by web/lib/deformer.js, which validates
// arguments before they get here; every method still runs in `guarded` and checks what it converts, so
// a failure reaches JS as an Error with a code and the C++ message, never as a wrapped-around number.
// Options cross through the one table of core/solver/solver_options.h, in both directions.
#include <emscripten/bind.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings/convert.h"
#include "core/mesh/vertex_normals.h"
#include "core/solver/deformer.h"
#include "core/solver/solver_options.h"

namespace sd::bindings {
namespace {

// IterationStats reach JS as value objects (their fields: EMSCRIPTEN_BINDINGS below); these are the fields that
// are computed for JS. The volume parts' arrays are there only with volume parts.
val line_search_to_js(const IterationStats& s) {
  val trials = val::array();
  for (const LineSearchTrial& t : s.line_search) trials.call<void>("push", val(t));
  return trials;
}

val stats_to_js(const IterationStats& s) {
  val out(s);
  if (!s.part_volume_change.empty()) {  // volume parts: per part, in part order
    val change = val::array(), lambda = val::array();
    for (double x : s.part_volume_change) change.call<void>("push", x);
    for (double x : s.part_lambda) lambda.call<void>("push", x);
    out.set("partVolumeChange", change);
    out.set("partLambda", lambda);
  }
  if (!s.bone_lambda.empty()) {  // a skeleton: its largest errors and each bone's length multiplier
    val lambda = val::array();
    for (double x : s.bone_lambda) lambda.call<void>("push", x);
    out.set("boneLengthError", s.bone_length_error);
    out.set("boneStraightnessError", s.bone_straightness_error);
    out.set("boneLambda", lambda);
  }
  return out;
}

// { joints: Float64Array (3 per joint, deformed), bones: [{ length, lengthError, straightnessError, lambda,
//   heldSamples, straightHard }], kept: false under ARAP }
val skeleton_report_to_js(const SkeletonReport& r) {
  val bones = val::array();
  for (const BoneReport& b : r.bones) {
    val bone = val::object();
    bone.set("length", b.length);
    bone.set("lengthError", b.length_error);
    bone.set("straightnessError", b.straightness_error);
    bone.set("lambda", b.lambda);
    bone.set("heldSamples", b.held_samples);
    bone.set("straightHard", b.straight_hard);
    bones.call<void>("push", bone);
  }
  val out = val::object();
  out.set("joints", to_js(r.joints));
  out.set("bones", bones);
  out.set("kept", r.kept);
  return out;
}

// { iterations, converged, stop: 'step_tolerance' | ..., stopReason: text for people }
val result_to_js(const StepResult& r) {
  val iterations = val::array();
  for (const IterationStats& s : r.iterations) iterations.call<void>("push", stats_to_js(s));
  val out = val::object();
  out.set("iterations", iterations);
  out.set("converged", r.converged);
  out.set("stop", std::string(stop_code_name(r.stop)));
  out.set("stopReason", r.stop_reason);
  return out;
}

// The keys of `o` applied to `next` through the options table. Unknown keys, wrong types and values
// outside the limits are refused, naming the option and its limit; null or undefined values are skipped.
SolverOptions options_from_js(const val& o, SolverOptions next) {
  if (o.typeOf().as<std::string>() != "object" || o.isNull()) throw Error("setOptions: options must be an object");
  const val keys = val::global("Object").call<val>("keys", o);
  const unsigned count = keys["length"].as<unsigned>();
  for (unsigned i = 0; i < count; ++i) {
    const std::string key = keys[i].as<std::string>();
    const OptionSpec* spec = find_solver_option(key);
    if (!spec) {
      std::string known;
      for (const OptionSpec& s : solver_option_table()) known += (known.empty() ? "" : ", ") + std::string(s.name);
      throw Error("setOptions: unknown option '" + key + "' (known: " + known + ")");
    }
    const val v = o[key];
    if (!present(v)) continue;
    double x = std::nan("");
    if (spec->kind == OptionKind::Choice && v.isString()) x = spec->choice_index(v.as<std::string>());
    if (spec->kind == OptionKind::Boolean && v.typeOf().as<std::string>() == "boolean") x = v.as<bool>() ? 1 : 0;
    if ((spec->kind == OptionKind::Integer || spec->kind == OptionKind::Number) && is_number(v)) x = v.as<double>();
    if (!spec->allows(x)) throw Error("setOptions: " + option_error_message(*spec, js_text(v)));
    spec->set(next, x);
  }
  return next;
}

val options_to_js(const SolverOptions& o) {
  val out = val::object();
  for (const OptionSpec& spec : solver_option_table()) {
    const double x = spec.get(o);
    switch (spec.kind) {
      case OptionKind::Choice: out.set(spec.name, std::string(spec.choices[static_cast<size_t>(x)])); break;
      case OptionKind::Boolean: out.set(spec.name, x != 0); break;
      case OptionKind::Integer: out.set(spec.name, static_cast<int>(x)); break;
      case OptionKind::Number: out.set(spec.name, x); break;
    }
  }
  return out;
}

// Whether `array` has an element at `index` (false for a hole of a sparse array).
bool has_element(const val& array, unsigned index) { return array.call<bool>("hasOwnProperty", index); }

// Handle groups from JS: an Array of Arrays or typed arrays of integers. A hole, a non-array, a non-integer or an
// integer beyond int is named here; whether the indices fit the mesh is the core's rule.
std::vector<std::vector<int>> handle_groups_from_js(const val& groups) {
  const val is_array = val::global("Array")["isArray"];
  const val is_view = val::global("ArrayBuffer")["isView"];
  if (!is_array(groups).as<bool>()) throw Error("handles: groups must be an array of arrays of vertex indices");
  std::vector<std::vector<int>> out;
  const unsigned count = groups["length"].as<unsigned>();
  for (unsigned g = 0; g < count; ++g) {
    const std::string group_name = "handles: group " + std::to_string(g);
    const val group = groups[g];
    if (!is_array(group).as<bool>() && !is_view(group).as<bool>())
      throw Error(group_name + (has_element(groups, g) ? " is not an array" : " is missing (a hole in the array)"));
    const unsigned size = group["length"].as<unsigned>();
    std::vector<int> vertices(size);
    for (unsigned k = 0; k < size; ++k) {
      const val v = group[k];
      const double x = is_number(v) ? v.as<double>() : std::nan("");
      if (!(std::isfinite(x) && x == std::floor(x)))
        throw Error(group_name + (has_element(group, k)
                                      ? " has a non-integer vertex index " + js_text(v)
                                      : " has no vertex at position " + std::to_string(k) + " (a hole in the array)"));
      if (x > INT_MAX || x < INT_MIN)
        throw Error(group_name + " has vertex " + js_text(v) + ", beyond what an int holds");
      vertices[k] = static_cast<int>(x);
    }
    out.push_back(std::move(vertices));
  }
  return out;
}

std::string arap_phase_name(const ArapHalfStep& h) { return h.local ? "local" : "global"; }

val strings_to_js(const std::vector<std::string>& strings) {
  val array = val::array();
  for (const std::string& s : strings) array.call<void>("push", s);
  return array;
}
val cage_warnings_to_js(const CageQuality& q) { return strings_to_js(q.warnings); }
val cage_warning_codes_to_js(const CageQuality& q) { return strings_to_js(q.warning_codes); }

class DeformerSession {
 public:
  explicit DeformerSession(std::unique_ptr<Deformer> d) : d_(std::move(d)) {}

  void set_options(const val& o) {
    guarded([&] { d_->set_options(options_from_js(o, d_->options())); });
  }
  val options() const {
    return guarded([&] { return options_to_js(d_->options()); });
  }

  // groups: an array of arrays (or typed arrays) of vertex indices. Only their shape is checked here; the rules
  // (no empty group, indices of the mesh, no vertex twice) are the core's (Deformer::set_handles).
  void set_handles(const val& groups) {
    guarded([&] { d_->set_handles(handle_groups_from_js(groups)); });
  }

  void set_targets(const val& targets) {
    guarded([&] { d_->set_targets(vertices_from_js(targets, "targets")); });
  }
  // Handle lines (core/solver/handle_line.h), 4 numbers per group: kind (0 none, 1 along, 2 from) and a 3-vector;
  // null or empty: none. web/lib/deformer.js (setHandleLines) builds them from { along } / { from } objects.
  void set_handle_lines(const val& lines) {
    guarded([&] {
      std::vector<HandleLine> per_group;
      if (present(lines)) {
        const unsigned length = lines["length"].as<unsigned>();
        if (length % 4 != 0)
          throw Error("setHandleLines: length " + std::to_string(length) + " is not a multiple of 4");
        std::vector<double> v(length);
        val(emscripten::typed_memory_view(v.size(), v.data())).call<void>("set", lines);
        for (unsigned g = 0; g < length / 4; ++g) {
          const double kind = v[4 * g];
          if (kind != 0 && kind != 1 && kind != 2) throw Error("setHandleLines: a line's kind must be 0, 1 or 2");
          per_group.push_back({kind == 0   ? HandleLine::Kind::None
                               : kind == 1 ? HandleLine::Kind::Along
                                           : HandleLine::Kind::From,
                               Eigen::Vector3d(v[4 * g + 1], v[4 * g + 2], v[4 * g + 3])});
        }
      }
      d_->set_handle_lines(per_group);
    });
  }
  // Per handle group, the largest distance of its vertices from their lines (or targets): a Float64Array.
  val handle_distances() const {
    return guarded([&] { return to_js(d_->handle_distances()); });
  }
  // k arrives as a JS number and is checked before it becomes an int (2**31 must not wrap to negative).
  val step(const val& k) {
    return guarded([&] { return result_to_js(d_->step(integer_in(k, "step: the number of iterations", 0, INT_MAX))); });
  }
  val solve() {
    return guarded([&] { return result_to_js(d_->solve()); });
  }
  // { phase: 'local' | 'global', energyBefore, energyAfter, meanRotation, maxRotation (radians), step }
  ArapHalfStep arap_half_step(const std::string& phase) {
    return guarded([&] {
      if (phase != "local" && phase != "global")
        throw Error("arapHalfStep: phase must be 'local' or 'global' (got '" + phase + "')");
      return d_->arap_half_step(phase == "local");
    });
  }
  void reset() {
    guarded([&] { d_->reset(); });
  }
  // { fitted, rule, samples, candidates, testError, reliable, ms }: the reduced integration's rule
  // (deformer.h).
  ReducedIntegrationInfo reduced_integration() const {
    return guarded([&] { return d_->reduced_integration(); });
  }
  void prepare_reduced() {
    guarded([&] { d_->prepare_reduced(); });
  }
  void prepare_factor() {
    guarded([&] { d_->prepare_factor(); });
  }
  double full_energy() const {
    return guarded([&] { return d_->full_energy(); });
  }
  val positions() const {
    return guarded([&] { return to_js(d_->positions()); });
  }
  val cage_positions() const {
    return guarded([&] { return to_js(d_->cage_positions()); });
  }
  // What the page draws, in the file's numbering: { positions, normals } as Float32Arrays (vertex normals of
  // core/mesh/vertex_normals.h, on the thread pool: in JS they cost as much as a solver iteration at 1M vertices).
  // setNormalGroups(groups: Int32Array | null, restNormals: Float32Array | null) sets the smoothing groups and the
  // file's normals once per model (web/lib/normals.js makes the groups); without it every vertex is its own.
  void set_normal_groups(const val& groups, const val& rest_normals) {
    guarded([&] {
      const std::vector<int> g =
          present(groups) ? emscripten::convertJSArrayToNumberVector<int>(groups) : std::vector<int>{};
      const std::vector<float> r =
          present(rest_normals) ? emscripten::convertJSArrayToNumberVector<float>(rest_normals) : std::vector<float>{};
      normals_ = std::make_unique<VertexNormals>(static_cast<int>(d_->rest_mesh().V.rows()), d_->rest_mesh().F, g, r);
    });
  }
  val render_buffers() {
    return guarded([&] {
      if (!normals_)
        normals_ = std::make_unique<VertexNormals>(static_cast<int>(d_->rest_mesh().V.rows()), d_->rest_mesh().F,
                                                   std::vector<int>{}, std::vector<float>{});
      const Vertices& X = d_->positions();
      const std::vector<float> positions(X.data(), X.data() + X.size());
      normals_->compute(X, normal_scratch_);
      val out = val::object();
      out.set("positions", val(emscripten::typed_memory_view(positions.size(), positions.data())).call<val>("slice"));
      out.set("normals",
              val(emscripten::typed_memory_view(normal_scratch_.size(), normal_scratch_.data())).call<val>("slice"));
      return out;
    });
  }
  double rest_volume() const { return d_->rest_volume(); }
  double bind_ms() const { return d_->bind_ms(); }
  double precompute_ms() const { return d_->precompute_ms(); }
  int vertex_count() const { return static_cast<int>(d_->rest_mesh().V.rows()); }
  int fallback_count() const { return d_->fallback_count(); }
  // { cageVertices, weakVertices, minColumnMax, volumeRatio, influenceRatio (NaN: not computed), weakMotions,
  //   sampledRows, ms, warnings: string[], poor } (core/basis/cage_quality.h); code no_cage without a cage or with
  //   the spectral basis.
  CageQuality cage_quality() const {
    return guarded([&] { return d_->cage_quality(); });
  }

  // What the session's layout did to the mesh (LayoutStats) and solverOfFile: per file vertex its solver vertex
  // (-1: carried along), for drawing one normal per welded point.
  val layout() const {
    return guarded([&] {
      val out = layout_stats_to_js(d_->layout().stats());
      out.set("solverOfFile", to_js(d_->layout().solver_of_file()));
      return out;
    });
  }
  // Warnings about the current result: [{ severity, code, message }] (mesh/deformation_check.h).
  val result_warnings() const {
    return guarded([&] { return findings_to_js(d_->result_findings()); });
  }

  // The skeleton: joints (3 numbers each, rest coordinates) and bones (2 joint indices each); null or no bones:
  // none. Joints whose coordinates are not finite are refused by the core, naming the joint.
  void set_skeleton(const val& joints, const val& bones) {
    guarded([&] {
      Skeleton s;
      if (present(joints)) s.joints = vertices_from_js(joints, "setSkeleton: joints");
      if (present(bones)) {
        const std::vector<int> ends = ints_from_js(bones, "setSkeleton: bone joint", 0, INT_MAX);
        if (ends.size() % 2 != 0)
          throw Error(ErrorCode::InvalidSkeleton,
                      "setSkeleton: bones need 2 joint indices each (got " + std::to_string(ends.size()) + ")");
        for (size_t b = 0; b < ends.size(); b += 2) s.bones.push_back({ends[b], ends[b + 1]});
      }
      d_->set_skeleton(s);
    });
  }
  // skeleton_report_to_js of the current positions; null without a skeleton.
  val skeleton_report() const {
    return guarded([&] {
      const std::optional<SkeletonReport> r = d_->skeleton_report();
      return r ? skeleton_report_to_js(*r) : val::null();
    });
  }

  // Volume parts: one part index per triangle (null or empty: the global volume).
  void set_volume_parts(const val& parts) {
    guarded([&] {
      if (!present(parts)) return d_->set_volume_parts({});
      d_->set_volume_parts(ints_from_js(parts, "setVolumeParts: part", 0, INT_MAX));
    });
  }
  val volume_parts() const {
    return guarded([&] { return to_js(d_->volume_parts()); });
  }
  val rest_part_volumes() const {
    return guarded([&] { return to_js(d_->rest_part_volumes()); });
  }
  val part_volumes() const {
    return guarded([&] { return to_js(d_->part_volumes()); });
  }

  std::string basis() const { return d_->basis_kind() == BasisKind::Spectral ? "spectral" : "cage"; }
  // What binding the cage's W found (coordinates_report_to_js, convert.h); null with the spectral basis or no cage.
  val coordinates_report() const {
    return guarded([&] {
      if (d_->basis_kind() != BasisKind::Cage || d_->rest_cage().F.rows() == 0) return val::null();
      return coordinates_report_to_js(d_->coordinates_report());
    });
  }
  // Column j of the basis (W or B) at every vertex of the file, as a Float32Array: what the page colours the mesh by
  // to show what one cage vertex (or spectral mode) controls.
  val basis_column(const val& column) const {
    return guarded([&] {
      const BasisMatrix& W = d_->basis();
      if (W.cols() == 0) throw Error(ErrorCode::NoCage, "basisColumn: this session has no subspace basis");
      const int j = integer_in(column, "basisColumn: the column", 0, W.cols() - 1);
      Eigen::VectorXd solver_column(W.rows());
      for (int i = 0; i < W.rows(); ++i) solver_column[i] = W.get(i, j);
      // In the file's numbering, like positions(): the page colours the mesh as the file lays it out.
      const Eigen::VectorXd column_of_file = d_->layout().values_to_file(solver_column);
      std::vector<float> values(static_cast<size_t>(column_of_file.size()));
      for (size_t i = 0; i < values.size(); ++i)
        values[i] = static_cast<float>(column_of_file[static_cast<Eigen::Index>(i)]);
      return val(emscripten::typed_memory_view(values.size(), values.data())).call<val>("slice");
    });
  }
  int basis_size() const { return d_->basis().cols(); }
  val basis_eigenvalues() const {
    return guarded([&] { return to_js(d_->basis_eigenvalues()); });
  }
  // The coefficients (P or C), row-major like positions: 3 numbers per basis column.
  val subspace_coefficients() const {
    return guarded([&] { return to_js(Vertices(d_->subspace_coefficients())); });
  }

 private:
  std::unique_ptr<Deformer> d_;
  std::unique_ptr<VertexNormals> normals_;  // renderBuffers(): made on the first call or by setNormalGroups
  std::vector<float> normal_scratch_;
};

// The basis from { basis?: 'cage' | 'spectral', modes?, coordinates?, pmvcResolution?, harmonicResolution? } plus
// the binding options (float32, memoryBudgetMB, progress), which apply to either basis; the coordinates (the cage
// basis' W) are refused with the spectral basis by the JS layer.
BasisOptions basis_from_js(const val& options, const val& progress) {
  BasisOptions basis;
  basis.cage = mvc_options_from_js(options, progress);
  basis.layout = layout_options_from_js(options);
  basis.coordinates = coordinates_from_js(options);
  if (!present(options) || options.typeOf().as<std::string>() != "object" || !present(options["basis"])) return basis;
  const val kind = options["basis"];
  if (kind.isString() && kind.as<std::string>() == "cage") return basis;
  if (!(kind.isString() && kind.as<std::string>() == "spectral"))
    throw Error("basis must be 'cage' or 'spectral' (got " + js_text(kind) + ")");
  basis.kind = BasisKind::Spectral;
  basis.spectral.modes = integer_in(options["modes"], "modes (the spectral basis' number of eigenvectors)", 1, INT_MAX);
  basis.spectral.single_precision = basis.cage.single_precision;
  basis.spectral.memory_budget_bytes = basis.cage.memory_budget_bytes;
  basis.spectral.progress = basis.cage.progress;
  return basis;
}

// new DeformerSession(meshPositions, meshIndices, cagePositions | null, cageIndices | null,
//                     { float32?, memoryBudgetMB?, basis?: 'cage' | 'spectral', modes?, weldTolerance?,
//                       coordinates?: 'mvc' | 'pmvc' | 'harmonic', pmvcResolution?, harmonicResolution? },
//                     onProgress?: (fraction) => boolean | void)
// onProgress returning false cancels binding the basis (Error with code 'cancelled').
DeformerSession* make_session(val mesh_positions, val mesh_indices, val cage_positions, val cage_indices, val options,
                              val progress) {
  return guarded([&] {
    const Mesh mesh = mesh_from_js(mesh_positions, mesh_indices, "mesh");
    Mesh cage{Vertices(0, 3), Faces(0, 3)};
    if (present(cage_positions)) cage = mesh_from_js(cage_positions, cage_indices, "cage");
    return new DeformerSession(std::make_unique<Deformer>(mesh, cage, basis_from_js(options, progress)));
  });
}

}  // namespace
}  // namespace sd::bindings

EMSCRIPTEN_BINDINGS(deformer) {
  using namespace sd;
  using namespace sd::bindings;
  using emscripten::value_object;
  // What the session returns, field by field as JS sees it (docs/library.md).
  value_object<LineSearchTrial>("LineSearchTrial")
      .field("alpha", &LineSearchTrial::alpha)
      .field("merit", &LineSearchTrial::merit)
      .field("sufficientDecrease", &LineSearchTrial::sufficient_decrease)
      .field("restored", &LineSearchTrial::restored);
  value_object<IterationStats>("IterationStats")
      .field("iteration", &IterationStats::iteration)
      .field("merit", &IterationStats::merit)
      .field("energy", &IterationStats::energy)
      .field("laplacianEnergy", &IterationStats::laplacian_energy)
      .field("positionEnergy", &IterationStats::position_energy)
      .field("straightnessEnergy", &IterationStats::straightness_energy)
      .field("regularizationEnergy", &IterationStats::regularization_energy)
      .field("volume", &IterationStats::volume)
      .field("volumeRelError", &IterationStats::volume_rel_error)
      .field("lambda", &IterationStats::lambda)
      .field("step", &IterationStats::step)
      .field("meritStart", &IterationStats::merit_start)
      .field("slope", &IterationStats::slope)
      .field("stepLength", &IterationStats::step_length)
      .field("alpha", &IterationStats::alpha)
      .field("lineSearch", &line_search_to_js, &to_js_only<IterationStats, val>)
      .field("lineSearchTrials", &IterationStats::line_search_trials)
      .field("innerIterations", &IterationStats::inner_iterations)
      .field("products", &IterationStats::products)
      .field("passes", &IterationStats::passes)
      .field("fallbacks", &IterationStats::fallbacks)
      .field("samples", &IterationStats::samples)
      .field("finishing", &IterationStats::finishing)
      .field("ms", &IterationStats::ms);
  value_object<ArapHalfStep>("ArapHalfStep")
      .field("phase", &arap_phase_name, &to_js_only<ArapHalfStep, std::string>)
      .field("energyBefore", &ArapHalfStep::energy_before)
      .field("energyAfter", &ArapHalfStep::energy_after)
      .field("meanRotation", &ArapHalfStep::mean_rotation)
      .field("maxRotation", &ArapHalfStep::max_rotation)
      .field("step", &ArapHalfStep::step);
  value_object<ReducedIntegrationInfo>("ReducedIntegrationInfo")
      .field("fitted", &ReducedIntegrationInfo::fitted)
      .field("rule", &ReducedIntegrationInfo::rule)
      .field("samples", &ReducedIntegrationInfo::samples)
      .field("candidates", &ReducedIntegrationInfo::candidates)
      .field("testError", &ReducedIntegrationInfo::test_error)
      .field("reliable", &ReducedIntegrationInfo::reliable)
      .field("ms", &ReducedIntegrationInfo::ms);
  value_object<CageQuality>("CageQuality")
      .field("cageVertices", &CageQuality::cage_vertices)
      .field("weakVertices", &CageQuality::weak_vertices)
      .field("minColumnMax", &CageQuality::min_column_max)
      .field("volumeRatio", &CageQuality::volume_ratio)
      .field("influenceRatio", &CageQuality::influence_ratio)
      .field("weakMotions", &CageQuality::weak_motions)
      .field("sampledRows", &CageQuality::sampled_rows)
      .field("ms", &CageQuality::ms)
      .field("warnings", &cage_warnings_to_js, &to_js_only<CageQuality, val>)
      .field("warningCodes", &cage_warning_codes_to_js, &to_js_only<CageQuality, val>)
      .field("poor", &CageQuality::poor, &to_js_only<CageQuality, bool>);

  emscripten::class_<DeformerSession>("DeformerSession")
      .constructor(&make_session)
      .function("setOptions", &DeformerSession::set_options)
      .function("options", &DeformerSession::options)
      .function("setHandles", &DeformerSession::set_handles)
      .function("setTargets", &DeformerSession::set_targets)
      .function("setHandleLines", &DeformerSession::set_handle_lines)
      .function("handleDistances", &DeformerSession::handle_distances)
      .function("step", &DeformerSession::step)
      .function("solve", &DeformerSession::solve)
      .function("arapHalfStep", &DeformerSession::arap_half_step)
      .function("reset", &DeformerSession::reset)
      .function("reducedIntegration", &DeformerSession::reduced_integration)
      .function("prepareReduced", &DeformerSession::prepare_reduced)
      .function("prepareFactor", &DeformerSession::prepare_factor)
      .function("fullEnergy", &DeformerSession::full_energy)
      .function("positions", &DeformerSession::positions)
      .function("cagePositions", &DeformerSession::cage_positions)
      .function("setNormalGroups", &DeformerSession::set_normal_groups)
      .function("renderBuffers", &DeformerSession::render_buffers)
      .function("restVolume", &DeformerSession::rest_volume)
      .function("bindMs", &DeformerSession::bind_ms)
      .function("precomputeMs", &DeformerSession::precompute_ms)
      .function("vertexCount", &DeformerSession::vertex_count)
      .function("fallbackCount", &DeformerSession::fallback_count)
      .function("setSkeleton", &DeformerSession::set_skeleton)
      .function("skeletonReport", &DeformerSession::skeleton_report)
      .function("setVolumeParts", &DeformerSession::set_volume_parts)
      .function("volumeParts", &DeformerSession::volume_parts)
      .function("restPartVolumes", &DeformerSession::rest_part_volumes)
      .function("partVolumes", &DeformerSession::part_volumes)
      .function("basis", &DeformerSession::basis)
      .function("coordinatesReport", &DeformerSession::coordinates_report)
      .function("basisColumn", &DeformerSession::basis_column)
      .function("basisSize", &DeformerSession::basis_size)
      .function("basisEigenvalues", &DeformerSession::basis_eigenvalues)
      .function("subspaceCoefficients", &DeformerSession::subspace_coefficients)
      .function("cageQuality", &DeformerSession::cage_quality)
      .function("layout", &DeformerSession::layout)
      .function("resultWarnings", &DeformerSession::result_warnings);
}
