#include "core/solver/deformer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "core/error.h"
#include "core/mesh/deformation_check.h"
#include "core/mesh/mesh_check.h"
#include "core/parts/partition.h"
#include "core/solver/internal/energy/component_anchors.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/gauss_newton.h"
#include "core/solver/internal/constraints/skeleton_constraints.h"
#include "core/solver/methods/arap_method.h"
#include "core/solver/methods/full_space_method.h"
#include "core/solver/methods/subspace_method.h"
#include "core/solver/solver_options.h"
#include "core/timer.h"

namespace sd {
namespace {

BasisOptions cage_basis(const MvcOptions& bind) {
  BasisOptions basis;
  basis.cage = bind;
  return basis;
}

// Throws sd::Error naming the first bad handle: an empty group, an index out of range, a vertex twice.
std::vector<int> flatten_handles(const std::vector<std::vector<int>>& groups, int vertex_count) {
  std::vector<int> flat;
  std::map<int, int> group_of;
  for (size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].empty()) throw Error("handles: group " + std::to_string(g) + " is empty");
    for (int v : groups[g]) {
      if (v < 0 || v >= vertex_count)
        throw Error("handles: group " + std::to_string(g) + " has vertex " + std::to_string(v) + " outside [0, " +
                    std::to_string(vertex_count) + ")");
      auto [it, inserted] = group_of.emplace(v, static_cast<int>(g));
      if (!inserted) {
        if (it->second == static_cast<int>(g))
          throw Error("handles: vertex " + std::to_string(v) + " appears twice in group " + std::to_string(g));
        throw Error("handles: vertex " + std::to_string(v) + " is in both group " + std::to_string(it->second) +
                    " and group " + std::to_string(g));
      }
      flat.push_back(v);
    }
  }
  return flat;
}

std::vector<int> group_sizes(const std::vector<std::vector<int>>& groups) {
  std::vector<int> sizes;
  for (const auto& g : groups) sizes.push_back(static_cast<int>(g.size()));
  return sizes;
}

// The table's limits (solver_options.h), then what depends on the session: the subspace method needs a basis
// (a cage, or the spectral basis).
void validate_options(const SolverOptions& o, bool has_subspace) {
  validate_solver_options(o);
  if (!has_subspace && o.method == Method::Subspace)
    throw Error(ErrorCode::NoCage,
                "solver options: the subspace method needs a cage or the spectral basis; this session has neither "
                "(use 'full' or 'arap')");
}

}  // namespace

struct Deformer::Impl {
  Mesh file_mesh;           // as given (the file's layout)
  MeshLayout layout;        // file <-> solver numbering (mesh_layout.h)
  Mesh mesh;                // the solver mesh: layout.mesh()
  HandleMap handle_map;     // the groups in solver numbering, and the file target row of each
  mutable Vertices file_X;  // positions() in the file layout, when the layout is not the identity
  mutable bool file_X_stale = true;
  Mesh cage;
  BasisKind basis = BasisKind::Cage;
  bool has_subspace = false;
  BasisMatrix W;                      // the cage's W or the spectral B
  Eigen::MatrixXd rest_coefficients;  // P0 (the rest cage) or C0, with W P0 = X0
  Eigen::VectorXd eigenvalues;        // spectral basis only
  double bind_ms = 0;
  CoordinatesReport coordinates;
  std::unique_ptr<DeformationEnergy> energy;
  SolverOptions options;
  std::vector<std::vector<int>> groups;
  std::vector<HandleLine> lines;  // per group, or empty
  std::vector<int> flat;          // handle vertices in group order (the order of the targets)
  // Components no handle holds, each held at rest by an anchor group (component_anchors.h); the energy's handles
  // are flat, then these.
  std::vector<std::vector<int>> anchors;

  // The methods used so far (method_solver.h), each made on first use; the subspace's when the session has a basis.
  std::unique_ptr<SubspaceMethod> subspace;
  std::unique_ptr<FullSpaceMethod> full;
  std::unique_ptr<ArapMethod> arap;

  Eigen::VectorXd bone_lambda;  // the skeleton's length multipliers of the last Gauss-Newton iteration
  GaussNewtonState state;       // X and the unknowns (P in the subspace, X in the full space)

  // The current method, made on first use.
  MethodSolver& method() {
    if (options.method == Method::Subspace) return *subspace;
    if (options.method == Method::Full) {
      if (!full) full = std::make_unique<FullSpaceMethod>(*energy);
      return *full;
    }
    return arap_method();
  }
  ArapMethod& arap_method() {
    if (!arap) arap = std::make_unique<ArapMethod>(mesh, *energy);
    return *arap;
  }

  // Null for a method not made yet.
  std::array<MethodSolver*, 3> methods_made() const { return {subspace.get(), full.get(), arap.get()}; }

  // The energy's handles, weights or lines changed: every method rebuilds what it made from them.
  void invalidate_methods() {
    for (MethodSolver* m : methods_made())
      if (m) m->invalidate();
  }

  // The energy's handle vertices: the user's (flat), then the anchors of the components none holds.
  std::vector<int> held() const {
    std::vector<int> out = flat;
    for (const auto& a : anchors) out.insert(out.end(), a.begin(), a.end());
    return out;
  }

  // The energy's targets: the user's rows, then the anchors' rest positions.
  Vertices with_anchor_targets(const Vertices& user) const {
    const std::vector<int> all = held();
    Vertices out(static_cast<Eigen::Index>(all.size()), 3);
    out.topRows(user.rows()) = user;
    for (size_t k = flat.size(); k < all.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = mesh.V.row(all[k]);
    return out;
  }

  // Whether components no handle holds need anchors: everywhere but in the cage subspace, where the cage carries
  // them along with the rest (eyes in a head follow the head).
  bool anchoring() const { return !(options.method == Method::Subspace && basis == BasisKind::Cage); }

  // Gives the energy the handle groups and the anchors of the components they leave free, targets at `user`
  // (the handle lines are cleared: apply_lines() puts them back).
  void set_energy_handles(const std::vector<std::vector<int>>& solver_groups, const Vertices& user) {
    flat = flatten_handles(solver_groups, static_cast<int>(mesh.V.rows()));
    anchors = anchoring() ? component_anchors(mesh.V, mesh.F, flat) : std::vector<std::vector<int>>();
    std::vector<int> sizes = group_sizes(solver_groups);
    for (const auto& a : anchors) sizes.push_back(static_cast<int>(a.size()));
    energy->set_handles(held(), sizes);
    energy->set_targets(with_anchor_targets(user));
  }

  // The groups' handle lines to the energy, one per vertex (anchors are point targets).
  void apply_lines() {
    std::vector<HandleLine> per_vertex;
    for (size_t g = 0; g < lines.size(); ++g)
      per_vertex.insert(per_vertex.end(), handle_map.groups[g].size(), lines[g]);
    if (!per_vertex.empty()) per_vertex.resize(held().size(), HandleLine{});
    energy->set_handle_lines(per_vertex);
  }

  // The subspace method over the current energy (its constant matrix B = (S L W)^T (S L W) and, for a cage, the
  // regulariser).
  void make_subspace_method() {
    subspace = std::make_unique<SubspaceMethod>(*energy, W, rest_coefficients, basis == BasisKind::Cage,
                                                options.cage_regularization);
  }

  // Re-weights the energy; what was built from it (the subspace's B and fits, the full space's factor) is rebuilt.
  void apply_weighting(EnergyWeighting weighting) {
    energy->set_weighting(weighting);
    if (has_subspace) make_subspace_method();
    full.reset();
    state.evaluation.reset();
    invalidate_methods();
  }

  // The skeleton's points' rows in the space of `method`: W^T m_q in the subspace (kept with the skeleton, where the
  // subspace's steps find them), m_q otherwise.
  const Eigen::MatrixXd& skeleton_rows(const SkeletonConstraints& skeleton, Method method) const {
    return method == Method::Subspace ? skeleton.rows_in(W) : skeleton.point_rows();
  }

  // Which bones can keep their middle hard in the space of `method` (skeleton_constraints.h); none without a
  // skeleton. Throws sd::Error (InvalidSkeleton) when even the lengths are dependent there. Changes nothing.
  std::vector<int> straight_bones(Method method) const {
    const SkeletonConstraints* skeleton = energy->skeleton();
    return skeleton ? skeleton->representable(skeleton_rows(*skeleton, method), method == Method::Subspace)
                    : std::vector<int>();
  }

  // Re-factors the current method now (so errors surface in the call that caused them) and marks the others
  // invalid.
  void refactor_current() {
    invalidate_methods();
    if (!flat.empty()) method().prepare(options);
  }

  // What the energy and the methods are configured from. A setter builds the next value and change() applies it;
  // when preparing the method fails, the same code applies the previous value again, so no setter undoes by hand.
  struct Configuration {
    SolverOptions options;
    std::vector<std::vector<int>> groups;  // the handle groups in solver numbering
    Vertices targets;                      // the user's targets, a row per handle vertex in group order
    std::vector<HandleLine> lines;         // per group, or empty
  };

  Configuration configuration() const {
    return {options, handle_map.groups, energy->targets().topRows(static_cast<Eigen::Index>(flat.size())), lines};
  }

  // Configures the energy for `next`, coming from `now`, and re-factors the current method when what it was made
  // from changed (prepare), or only marks the methods invalid (a rollback: `now` was prepared before). `rehandle`
  // sets the handles and re-factors even when they are the same (set_handles: a new handle set starts afresh).
  void apply(const Configuration& next, const Configuration& now, bool prepare, bool rehandle) {
    const bool method_changed = next.options.method != now.options.method;
    // What the new method's space can keep of the skeleton, before anything changes: its refusal costs nothing.
    const std::vector<int> straight = method_changed ? straight_bones(next.options.method) : std::vector<int>();
    options = next.options;
    const bool weighting_changed = next.options.weighting != energy->weighting();
    const bool handles_changed = next.groups != now.groups || next.targets.rows() != now.targets.rows() ||
                                 next.targets != now.targets;  // Eigen compares only matrices of one size
    // Only what changed is set: each setter of the energy makes its handle terms new (their version).
    if (weighting_changed) apply_weighting(next.options.weighting);
    const bool weight_changed = next.options.position_weight != energy->position_weight();
    if (weight_changed) energy->set_position_weight(next.options.position_weight);
    // The straightness term exists only with a skeleton: without one a new weight changes no factor.
    const bool straightness_changed = next.options.straightness_weight != energy->straightness_weight();
    if (straightness_changed) energy->set_straightness_weight(next.options.straightness_weight);
    const bool term_changed = straightness_changed && energy->skeleton() != nullptr;
    // The anchors depend on the method (anchoring()); the energy's set_handles clears the lines.
    const bool rehandled = rehandle || handles_changed || (method_changed && !next.groups.empty());
    if (rehandled) set_energy_handles(next.groups, next.targets);
    const bool lines_changed = next.lines != now.lines;
    lines = next.lines;
    if (rehandled || lines_changed) apply_lines();
    // (The evaluation's skeleton entries may hold other middles: set_options resets the state after a switch.)
    if (method_changed && energy->skeleton()) energy->keep_bones_straight(straight);
    if (!(method_changed || weighting_changed || weight_changed || term_changed || rehandled || lines_changed)) return;
    if (prepare) refactor_current();
    else invalidate_methods();
  }

  // Applies `next`; if that throws, applies the configuration before it again and rethrows.
  void change(const Configuration& next, bool rehandle = false) {
    const Configuration now = configuration();
    try {
      apply(next, now, true, rehandle);
    } catch (...) {
      apply(now, next, false, false);
      throw;
    }
  }

  void reset() {
    file_X_stale = true;
    state.X = mesh.V;
    state.U = options.method == Method::Subspace ? rest_coefficients : Eigen::MatrixXd(mesh.V);
    state.iteration = 0;
    state.evaluation.reset();
    for (MethodSolver* m : methods_made())
      if (m) m->forget_history();
  }

  StepResult run(int k, StopCode cap) {
    if (k < 0) throw Error("step: the number of iterations must be >= 0 (got " + std::to_string(k) + ")");
    file_X_stale = true;
    if (k == 0 || flat.empty()) {
      StepResult nothing;
      nothing.finish(k == 0 ? StopCode::NoIterations : StopCode::NoHandles);
      return nothing;
    }
    const StepResult result = method().run(state, k, options, cap);
    if (!result.iterations.empty()) {
      const std::vector<double>& lambda = result.iterations.back().bone_lambda;
      bone_lambda = Eigen::Map<const Eigen::VectorXd>(lambda.data(), static_cast<Eigen::Index>(lambda.size()));
    }
    return result;
  }
};

Deformer::Deformer(const Mesh& mesh, const Mesh& cage, const MvcOptions& bind)
    : Deformer(mesh, cage, cage_basis(bind)) {}

Deformer::Deformer(const Mesh& mesh, const Mesh& cage, const BasisOptions& basis) : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  const bool has_cage = cage.F.rows() > 0;
  const bool spectral = basis.kind == BasisKind::Spectral;
  d.layout = MeshLayout(mesh, basis.layout);
  if (has_cage && !spectral) {
    // The budget first: checking a large pair takes long, and an oversized W is refused anyway.
    check_weights_budget(static_cast<int>(d.layout.mesh().V.rows()), static_cast<int>(cage.V.rows()), basis.cage);
    throw_if_invalid(check_model_in_cage(d.layout, cage));
  } else {
    throw_if_invalid(check_model(d.layout));
  }
  d.file_mesh = mesh;
  d.mesh = d.layout.mesh();
  d.cage = has_cage ? cage : Mesh{Vertices(0, 3), Faces(0, 3)};
  d.basis = basis.kind;
  d.energy = std::make_unique<DeformationEnergy>(d.mesh.V, d.mesh.F, d.options.weighting);
  d.energy->set_straightness_weight(d.options.straightness_weight);
  const double t0 = now_ms();
  if (spectral) {
    SpectralBasis B = spectral_basis(d.mesh, basis.spectral);
    d.W = std::move(B.B);
    d.rest_coefficients = std::move(B.rest_coefficients);
    d.eigenvalues = std::move(B.eigenvalues);
  } else if (has_cage) {
    d.W = cage_coordinates(d.mesh.V, cage, basis.cage, basis.coordinates, &d.coordinates);
    d.rest_coefficients = cage.V;
  }
  d.has_subspace = spectral || has_cage;
  if (d.has_subspace) {
    d.bind_ms = now_ms() - t0;
    d.make_subspace_method();
  } else {
    d.options.method = Method::Full;
  }
  d.reset();
}

Deformer::~Deformer() = default;

void Deformer::set_options(const SolverOptions& options) {
  Impl& d = *impl_;
  validate_options(options, d.has_subspace);
  const SolverOptions old = d.options;
  Impl::Configuration next = d.configuration();
  next.options = options;
  d.change(next);
  if (old.method != options.method) d.reset();
  else if (old.integration != options.integration) d.state.evaluation.reset();  // the energy is summed differently
}

const SolverOptions& Deformer::options() const { return impl_->options; }

void Deformer::set_handles(const std::vector<std::vector<int>>& groups) {
  Impl& d = *impl_;
  flatten_handles(groups, d.layout.file_vertex_count());  // names the first bad handle in the file's numbers
  HandleMap map = d.layout.map_handles(groups);
  const std::vector<int> flat = flatten_handles(map.groups, static_cast<int>(d.mesh.V.rows()));
  Impl::Configuration next = d.configuration();
  next.groups = map.groups;
  next.targets.resize(static_cast<Eigen::Index>(flat.size()), 3);  // the handles start where they are
  for (size_t k = 0; k < flat.size(); ++k) next.targets.row(static_cast<Eigen::Index>(k)) = d.state.X.row(flat[k]);
  next.lines.clear();  // a line belongs to its group
  d.change(next, true);
  d.groups = groups;
  d.handle_map = std::move(map);
  if (d.arap) d.arap->forget_history();
}

void Deformer::set_handle_lines(const std::vector<HandleLine>& per_group) {
  Impl& d = *impl_;
  if (!per_group.empty() && per_group.size() != d.groups.size())
    throw Error("handle lines: " + std::to_string(per_group.size()) + " lines for " + std::to_string(d.groups.size()) +
                " handle groups");
  for (size_t g = 0; g < per_group.size(); ++g)
    validate_handle_line(per_group[g], ("handle lines: group " + std::to_string(g)).c_str());
  const std::vector<HandleLine> old = d.lines;
  d.lines = per_group;
  d.apply_lines();
  // The preconditioners hold the lines' directions (subspace_step.h, full_space_step.h): remade on the next step.
  if (per_group != old) {
    if (d.subspace) d.subspace->invalidate();
    if (d.full) d.full->invalidate();
  }
}

const std::vector<HandleLine>& Deformer::handle_lines() const { return impl_->lines; }

Eigen::VectorXd Deformer::handle_distances() const {
  const Impl& d = *impl_;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(d.handle_map.groups.size()));
  Eigen::Index row = 0;
  for (size_t g = 0; g < d.handle_map.groups.size(); ++g)
    for (int v : d.handle_map.groups[g]) {
      const Eigen::RowVector3d offset = d.state.X.row(v) - d.energy->targets().row(row);
      out[static_cast<Eigen::Index>(g)] =
          std::max(out[static_cast<Eigen::Index>(g)], d.energy->across_line(row, offset).norm());
      ++row;
    }
  return out;
}

const std::vector<std::vector<int>>& Deformer::handles() const { return impl_->groups; }

void Deformer::set_targets(const Vertices& file_targets) {
  Impl& d = *impl_;
  if (file_targets.rows() != d.handle_map.file_rows)
    throw Error("targets: " + std::to_string(file_targets.rows()) + " rows (" +
                std::to_string(3 * file_targets.rows()) + " numbers) for " + std::to_string(d.handle_map.file_rows) +
                " handle vertices (expected " + std::to_string(3 * d.handle_map.file_rows) + " numbers)");
  Eigen::Index r = 0;
  for (const std::vector<int>& group : d.groups)
    for (int v : group) {
      if (!file_targets.row(r).allFinite())
        throw Error("targets: the target of handle vertex " + std::to_string(v) + " (row " + std::to_string(r) +
                    ") is not finite");
      ++r;
    }
  const Vertices targets = d.with_anchor_targets(d.layout.solver_targets(d.handle_map, file_targets));
  // Same targets again (an app re-sending them each frame) keep the ARAP stopping rule's history.
  if (targets != d.energy->targets() && d.arap) d.arap->forget_history();
  d.energy->set_targets(targets);
}

void Deformer::set_volume_parts(const std::vector<int>& part_of_face) {
  Impl& d = *impl_;
  std::vector<int> solver_parts;
  if (!part_of_face.empty()) {
    validate_parts(part_of_face, d.layout.file_face_count());
    solver_parts = d.layout.solver_face_parts(part_of_face);
  }
  d.energy->set_volume_parts(solver_parts);
  d.state.evaluation.reset();  // its constraint values belong to the old parts
}

void Deformer::set_skeleton(const Skeleton& skeleton) {
  Impl& d = *impl_;
  if (skeleton.empty()) {
    validate_skeleton(skeleton, d.mesh, true);  // joints without bones are an error, not "none"
    d.energy->set_skeleton(nullptr);
  } else {
    validate_skeleton(skeleton, d.mesh, d.energy->boundary_vertex_count() == 0);
    auto constraints = std::make_unique<SkeletonConstraints>(skeleton, d.mesh);
    constraints->keep_straight(constraints->representable(d.skeleton_rows(*constraints, d.options.method),
                                                          d.options.method == Method::Subspace));
    d.energy->set_skeleton(std::move(constraints));
  }
  d.bone_lambda.resize(0);
  d.state.evaluation.reset();  // its skeleton entries belong to the old one
  // The straightness term is part of the Gauss-Newton methods' factors; ARAP ignores the skeleton, so under it they
  // are only marked to be remade.
  if (d.options.straightness_weight > 0.0) {
    if (d.options.method == Method::Arap) d.invalidate_methods();
    else d.refactor_current();
  }
}

Skeleton Deformer::skeleton() const {
  const SkeletonConstraints* s = impl_->energy->skeleton();
  return s ? s->skeleton() : Skeleton{};
}

std::optional<SkeletonReport> Deformer::skeleton_report() const {
  const Impl& d = *impl_;
  const SkeletonConstraints* s = d.energy->skeleton();
  if (!s) return std::nullopt;
  SkeletonReport report = s->report(s->points(d.state.X), d.bone_lambda);
  if (d.options.method == Method::Arap) {
    report.kept = false;
    for (BoneReport& bone : report.bones) {
      bone.lambda = 0;
      bone.held_samples = 0;
      bone.straight_hard = false;
    }
  }
  return report;
}

std::vector<int> Deformer::volume_parts() const { return impl_->layout.file_face_parts(impl_->energy->volume_parts()); }

Eigen::VectorXd Deformer::rest_part_volumes() const { return impl_->energy->rest_constraint_volumes(); }

Eigen::VectorXd Deformer::part_volumes() const {
  const Impl& d = *impl_;
  return d.energy->constraints(d.state.X) + d.energy->rest_constraint_volumes();
}

StepResult Deformer::step(int iterations) { return impl_->run(iterations, StopCode::IterationLimit); }

StepResult Deformer::solve() { return impl_->run(impl_->options.max_iterations, StopCode::MaxIterations); }

void Deformer::reset() { impl_->reset(); }

ArapHalfStep Deformer::arap_half_step(bool local) {
  Impl& d = *impl_;
  if (d.options.method != Method::Arap) throw Error("arap half step: the method is not arap");
  if (d.flat.empty()) throw Error("arap half step: no handles");
  const ArapHalfStep half = d.arap_method().half_step(d.state, local, d.options);
  if (!local) d.file_X_stale = true;
  return half;
}

const Vertices& Deformer::positions() const {
  const Impl& d = *impl_;
  if (d.layout.identity()) return d.state.X;
  if (d.file_X_stale) {
    d.file_X = d.layout.to_file(d.state.X);
    d.file_X_stale = false;
  }
  return d.file_X;
}

Vertices Deformer::cage_positions() const {
  const Impl& d = *impl_;
  if (d.options.method == Method::Subspace && d.basis == BasisKind::Cage) return d.state.U;
  return d.cage.V;
}

const Eigen::MatrixXd& Deformer::subspace_coefficients() const {
  const Impl& d = *impl_;
  return d.options.method == Method::Subspace ? d.state.U : d.rest_coefficients;
}

const Mesh& Deformer::rest_mesh() const { return impl_->file_mesh; }
const MeshLayout& Deformer::layout() const { return impl_->layout; }
const Mesh& Deformer::rest_cage() const { return impl_->cage; }
BasisKind Deformer::basis_kind() const { return impl_->basis; }
const BasisMatrix& Deformer::basis() const { return impl_->W; }
const Eigen::VectorXd& Deformer::basis_eigenvalues() const { return impl_->eigenvalues; }
double Deformer::rest_volume() const { return impl_->energy->rest_volume(); }
double Deformer::bind_ms() const { return impl_->bind_ms; }
const CoordinatesReport& Deformer::coordinates_report() const { return impl_->coordinates; }
double Deformer::precompute_ms() const { return impl_->subspace ? impl_->subspace->precompute_ms() : 0.0; }
int Deformer::fallback_count() const { return impl_->energy->fallback_count(); }

std::vector<Finding> Deformer::result_findings() const {
  const Impl& d = *impl_;
  const IndexNames names = d.layout.names();
  return check_deformation(d.mesh, d.state.X, d.cage, cage_positions(), &names);
}

ReducedIntegrationInfo Deformer::reduced_integration() const {
  ReducedIntegrationInfo info;
  if (!impl_->subspace) return info;
  if (const auto& rule = impl_->subspace->reduced_rule()) {
    info.fitted = true;
    info.rule = rule->clusters ? "clusters" : "every vertex";
    info.samples = rule->samples;
    info.candidates = rule->candidates;
    info.test_error = rule->test_error;
    info.reliable = rule->test_error <= kReducedTestErrorLimit;
    info.ms = rule->ms;
  }
  return info;
}

void Deformer::prepare_reduced() {
  Impl& d = *impl_;
  if (!d.has_subspace)
    throw Error(ErrorCode::NoCage, "reduced integration: this session has no subspace (no cage, no spectral basis)");
  d.subspace->prepare_reduced();
}

void Deformer::prepare_factor() {
  Impl& d = *impl_;
  if (d.options.method == Method::Subspace && d.subspace) d.subspace->prepare_factor(d.options);
}

bool Deformer::factor_prepared() const { return impl_->subspace && impl_->subspace->factor_prepared(); }

double Deformer::full_energy() const {
  const Impl& d = *impl_;
  const double regularization =
      d.options.method == Method::Subspace && d.subspace ? d.subspace->regularization_energy(d.state.U) : 0.0;
  return d.energy->evaluate(d.state.X).energy + regularization;
}

CageQuality Deformer::cage_quality(const CageQualityOptions& options) const {
  const Impl& d = *impl_;
  // With the spectral basis W holds the basis B, not cage coordinates: there is no cage to judge.
  if (d.basis != BasisKind::Cage || d.cage.F.rows() == 0)
    throw Error(ErrorCode::NoCage, "cage quality: this session has no cage (no cage, or the spectral basis)");
  return sd::cage_quality(d.W, d.mesh, d.cage, options);
}

}  // namespace sd
