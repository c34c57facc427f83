#include "core/mesh/mesh_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/geometry/point_triangle_distance.h"
#include "core/geometry/self_intersection.h"
#include "core/geometry/winding_number.h"
#include "core/mesh/topology.h"
#include "core/mesh/volume.h"
#include "core/parallel/parallel_for.h"
#include "core/parts/part_volume.h"

namespace sd {
namespace {

// |coordinate| above this is reported (as a warning: the algorithms are scale-free, but such values
// usually mean wrong units or garbage, and products like volume lose relative precision).
constexpr double kHugeCoordinate = 1e12;
// A closed mesh whose |volume| is below this times the cubed bounding-box diagonal encloses nothing.
constexpr double kFlatVolumeRatio = 1e-12;
// A face is degenerate when its area is below this times the squared bounding-box diagonal.
constexpr double kDegenerateAreaRatio = 1e-14;
// A mesh vertex closer than this times the cage's bounding-box diagonal is "on" the cage surface.
constexpr double kOnSurfaceRatio = 1e-9;
constexpr size_t kShown = 5;                   // offending indices listed per message
constexpr int kMaxCrossingsListed = 100;       // self-intersecting face pairs counted before stopping
constexpr double kFoldedFlatCos = -1 + 1e-10;  // two faces of an edge this close to opposite overlap

// "12, 40, 77, ..." -- the first few items of a list.
template <class T, class Format>
std::string first_few(const std::vector<T>& items, Format format) {
  std::string out;
  for (size_t i = 0; i < items.size() && i < kShown; ++i) out += (i ? ", " : "") + format(items[i]);
  if (items.size() > kShown) out += " ...";
  return out;
}
std::string first_few(const std::vector<int>& items) {
  return first_few(items, [](int i) { return std::to_string(i); });
}
std::string edge_text(const std::pair<int, int>& e) { return std::to_string(e.first) + "-" + std::to_string(e.second); }
std::string number(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}
// "1 face", "3 faces"; "1 vertex", "2 vertices".
std::string plural(size_t n, const std::string& word) {
  if (n == 1) return "1 " + word;
  return std::to_string(n) + " " + (word == "vertex" ? "vertices" : word + "s");
}

class Reporter {
 public:
  Reporter(CheckReport* report, const std::string& role, const IndexNames* names)
      : report_(report), prefix_(role.empty() ? "" : role + ": "), names_(names) {}
  void error(const std::string& code, const std::string& message) { add(Severity::Error, code, message); }
  void warning(const std::string& code, const std::string& message) { add(Severity::Warning, code, message); }
  void note(const std::string& code, const std::string& message) { add(Severity::Note, code, message); }
  // Vertex and face numbers as the user knows them (the file's, through the layout's names).
  int vertex(int v) const { return names_ ? names_->vertex[v] : v; }
  int face(int f) const { return names_ ? names_->face[f] : f; }
  std::string vertices(const std::vector<int>& list) const {
    return first_few(list, [&](int v) { return std::to_string(vertex(v)); });
  }
  std::string faces(const std::vector<int>& list) const {
    return first_few(list, [&](int f) { return std::to_string(face(f)); });
  }
  std::string edges(const std::vector<std::pair<int, int>>& list) const {
    return first_few(list, [&](const std::pair<int, int>& e) {
      return edge_text({vertex(e.first), vertex(e.second)});
    });
  }

 private:
  void add(Severity s, const std::string& code, const std::string& message) {
    report_->findings.push_back({s, code, prefix_ + message});
  }
  CheckReport* report_;
  std::string prefix_;
  const IndexNames* names_;
};

// What the steps of check_mesh learn and later steps use.
struct Facts {
  int nv = 0, nf = 0;
  std::vector<char> finite;                // per vertex
  std::vector<int> non_finite, too_large;  // vertices
  double diagonal = 0;
  std::vector<int> bad_index, repeated;  // faces
  std::vector<int> in_range;             // faces whose indices are all valid (repeated ones included)
  std::vector<int> topo;                 // faces usable for connectivity (indices valid and distinct)
  std::vector<char> referenced;          // per vertex
  std::vector<std::pair<int, int>> boundary, non_manifold, misoriented;
  std::vector<int> bowties;
  std::vector<int> unreferenced;
  std::vector<int> component_of_face;  // per topo face (in topo order), after components()
  int components = 0;
  // Edge- and vertex-manifold and consistently oriented (open or closed): volumes mean something.
  bool manifold() const {
    return nf > 0 && bad_index.empty() && repeated.empty() && non_manifold.empty() && misoriented.empty() &&
           bowties.empty();
  }
};

// Coordinates: non-finite and huge values; the bounding box of the finite ones.
void check_coordinates(const Mesh& m, Reporter& out, MeshSummary& s, Facts& facts) {
  std::vector<int> huge;
  facts.finite.assign(static_cast<size_t>(facts.nv), 1);
  bool any_finite = false;
  for (int i = 0; i < facts.nv; ++i) {
    const Eigen::RowVector3d p = m.V.row(i);
    if (!p.allFinite()) {
      facts.finite[i] = 0;
      facts.non_finite.push_back(i);
      continue;
    }
    if (p.cwiseAbs().maxCoeff() > kMaxMeshCoordinate) facts.too_large.push_back(i);
    else if (p.cwiseAbs().maxCoeff() > kHugeCoordinate) huge.push_back(i);
    s.bbox_min = any_finite ? s.bbox_min.cwiseMin(p) : p;
    s.bbox_max = any_finite ? s.bbox_max.cwiseMax(p) : p;
    any_finite = true;
  }
  if (!facts.non_finite.empty())
    out.error("non_finite", "NaN or infinite coordinates in " + std::to_string(facts.non_finite.size()) + " of " +
                                plural(facts.nv, "vertex") + " (first: " + out.vertices(facts.non_finite) + ")");
  if (!facts.too_large.empty())
    out.error("coordinates_too_large",
              "coordinates beyond 1e30 in magnitude in " + plural(facts.too_large.size(), "vertex") +
                  " (first: " + out.vertices(facts.too_large) + "); volumes would overflow: rescale the model");
  if (!huge.empty())
    out.warning("huge_coordinates", "coordinates beyond 1e12 in magnitude in " + plural(huge.size(), "vertex") +
                                        " (first: " + out.vertices(huge) + "); check the units");
  facts.diagonal = (s.bbox_max - s.bbox_min).norm();
}

// Faces: index range, repeated indices, zero area.
void check_faces(const Mesh& m, Reporter& out, Facts& facts) {
  const int nv = facts.nv;
  const double diag = facts.diagonal;
  std::vector<int> zero_area;
  facts.referenced.assign(static_cast<size_t>(nv), 0);
  for (int f = 0; f < facts.nf; ++f) {
    const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
    if (a < 0 || a >= nv || b < 0 || b >= nv || c < 0 || c >= nv) {
      facts.bad_index.push_back(f);
      continue;
    }
    facts.in_range.push_back(f);
    facts.referenced[a] = facts.referenced[b] = facts.referenced[c] = 1;
    if (a == b || b == c || c == a) {
      facts.repeated.push_back(f);
      continue;
    }
    facts.topo.push_back(f);
    if (facts.finite[a] && facts.finite[b] && facts.finite[c]) {
      const double area = 0.5 * (m.V.row(b) - m.V.row(a)).cross(m.V.row(c) - m.V.row(a)).norm();
      // Skipped when the coordinates are too large to square (already an error of their own).
      if (facts.too_large.empty() && !(area > kDegenerateAreaRatio * diag * diag)) zero_area.push_back(f);
    }
  }
  if (!facts.bad_index.empty())
    out.error("index_out_of_range", plural(facts.bad_index.size(), "face") + " with vertex indices outside 0.." +
                                        std::to_string(nv - 1) + " (first: " +
                                        first_few(facts.bad_index,
                                                  [&](int f) {
                                                    return "face " + std::to_string(out.face(f)) + " (" +
                                                           std::to_string(m.F(f, 0)) + " " + std::to_string(m.F(f, 1)) +
                                                           " " + std::to_string(m.F(f, 2)) + ")";
                                                  }) +
                                        ")");
  const std::vector<int>& repeated = facts.repeated;
  if (!repeated.empty() || !zero_area.empty()) {
    std::string message = plural(repeated.size() + zero_area.size(), "degenerate face") + ":";
    if (!repeated.empty())
      message += " " + std::to_string(repeated.size()) + " with a repeated vertex (first: " + out.faces(repeated) + ")";
    if (!zero_area.empty())
      message += std::string(repeated.empty() ? "" : ";") + " " + std::to_string(zero_area.size()) +
                 " with zero area (below 1e-14 x bbox diagonal^2; first: " + out.faces(zero_area) + ")";
    out.error("degenerate_face", message);
  }
}

// Faces with the same three vertices (either orientation).
void check_duplicates(const Mesh& m, Reporter& out, const Facts& facts) {
  const std::vector<std::pair<int, int>> duplicates = duplicate_faces(m.F, facts.topo);
  if (!duplicates.empty())
    out.error("duplicate_face", plural(duplicates.size(), "duplicate face") + " (same three vertices; first: " +
                                    first_few(duplicates,
                                              [&](const std::pair<int, int>& d) {
                                                return "faces " + std::to_string(out.face(d.first)) + " and " +
                                                       std::to_string(out.face(d.second));
                                              }) +
                                    ")");
}

// Edges: boundary (1 face), non-manifold (> 2 faces), orientation (both faces walk it the same way).
void check_edges(const Mesh& m, Reporter& out, MeshSummary& s, Facts& facts, bool open_allowed) {
  const EdgeUses edges(m.F, facts.topo);
  s.edges = static_cast<int>(edges.edges().size());
  for (const Edge& e : edges.edges()) {
    if (e.boundary()) facts.boundary.push_back({e.lo, e.hi});
    if (e.non_manifold()) facts.non_manifold.push_back({e.lo, e.hi});
    if (e.misoriented()) facts.misoriented.push_back({e.lo, e.hi});
  }
  s.holes = boundary_loop_count(edges);
  if (!facts.boundary.empty() && open_allowed)
    out.note("open", "the mesh is open: " + plural(facts.boundary.size(), "boundary edge") + " around " +
                         plural(static_cast<size_t>(s.holes), "hole") + " (first: " + out.edges(facts.boundary) +
                         "); for the volume each hole is closed by the fan from its centroid");
  else if (!facts.boundary.empty())
    out.error("open", "the mesh is open: " + plural(facts.boundary.size(), "boundary edge") +
                          " (used by a single face; first: " + out.edges(facts.boundary) + ")");
  if (!facts.non_manifold.empty())
    out.error("non_manifold_edge", plural(facts.non_manifold.size(), "non-manifold edge") +
                                       " (shared by more than two faces; first: " + out.edges(facts.non_manifold) +
                                       ")");
  if (!facts.misoriented.empty())
    out.error("inconsistent_orientation",
              "inconsistent orientation: " + plural(facts.misoriented.size(), "edge") +
                  " walked in the same direction by both of their faces (first: " + out.edges(facts.misoriented) +
                  "); neighbouring faces must have opposite edge directions");
  facts.bowties = non_manifold_vertices(m.F, facts.nv, facts.topo);
  if (!facts.bowties.empty())
    out.error("non_manifold_vertex",
              plural(facts.bowties.size(), "non-manifold vertex") +
                  " (the faces around each form several separate fans; first: " + out.vertices(facts.bowties) + ")");
}

// Vertices no face uses.
void check_unreferenced(Reporter& out, Facts& facts) {
  for (int i = 0; i < facts.nv; ++i)
    if (!facts.referenced[i]) facts.unreferenced.push_back(i);
  if (!facts.unreferenced.empty() && facts.nf > 0)
    out.warning("unreferenced_vertices", plural(facts.unreferenced.size(), "vertex") +
                                             " used by no face (first: " + out.vertices(facts.unreferenced) +
                                             "); they are ignored by the cage but kept");
}

// Connected components (through shared vertices), numbered per topo face.
void check_components(const Mesh& m, Reporter& out, MeshSummary& s, Facts& facts, bool model_rules,
                      const std::string& role) {
  const Components components = connected_components(m.F, facts.nv, facts.in_range);
  facts.components = components.count;
  for (int f : facts.topo) facts.component_of_face.push_back(components.of_face[f]);
  s.components = facts.components;
  if (facts.components > 1 && model_rules)
    out.note("components", "the mesh has " + std::to_string(facts.components) +
                               " separate components; each keeps its own volume, and the same cage deforms them all");
  else if (facts.components > 1 && role == "cage")
    out.warning("components", "the cage has " + std::to_string(facts.components) +
                                  " separate components; a cage is one closed surface (one split at its seams, each "
                                  "face with its own corners as glTF writes flat-shaded boxes, must be welded)");
  else if (facts.components > 1)
    out.warning("components", "the mesh has " + std::to_string(facts.components) +
                                  " separate components; each is deformed with the same cage");
}

// The faces the topology was found on (facts.topo), in that order: facts.component_of_face indexes them.
Faces topo_faces(const Mesh& m, const Facts& facts) {
  Faces F(static_cast<Eigen::Index>(facts.topo.size()), 3);
  for (size_t r = 0; r < facts.topo.size(); ++r) F.row(static_cast<Eigen::Index>(r)) = m.F.row(facts.topo[r]);
  return F;
}

// Signed volume per component: the sum of the triangles' tetrahedra, or, for an open manifold mesh under the
// model rules, with each hole capped (part_volume.h) so that it means the same as the solver's. Summed about the
// mesh's own volume_reference (volume.h), so that a model far from the origin reads as it does at the origin.
Eigen::VectorXd component_volumes(const Mesh& m, const Faces& F, const Facts& facts, bool capped) {
  const VolumeReference o = volume_reference(m.V, F);
  if (capped) {
    try {
      return PartVolumes(F, facts.nv, facts.component_of_face).evaluate(m.V, o);
    } catch (const Error&) {
      // An edge walked twice the same way (duplicated faces): not capped; the errors already say why.
    }
  }
  // A triangle with a non-finite corner has no volume to add: the others are summed.
  std::vector<int> component(facts.component_of_face);
  const int count = std::max(facts.components, 1);
  for (Eigen::Index r = 0; r < F.rows(); ++r)
    if (!facts.finite[F(r, 0)] || !facts.finite[F(r, 1)] || !facts.finite[F(r, 2)]) component[r] = count;
  return signed_volumes(m.V, F, component, count + 1, o).head(count);
}

// Orientation and genus only mean something for a closed (or, under the model rules, capped), consistently
// oriented manifold.
void check_volume_and_genus(const Mesh& m, Reporter& out, MeshSummary& s, const Facts& facts, bool model_rules) {
  const bool open = !facts.boundary.empty();
  const bool measurable = facts.manifold() && (!open || model_rules);
  const bool capped = measurable && open && facts.non_finite.empty();
  const Faces F = topo_faces(m, facts);
  const Eigen::VectorXd component_volume = component_volumes(m, F, facts, capped);
  const double volume = component_volume.sum();
  s.volume = volume;
  const double diag = facts.diagonal;
  // Beyond kMaxMeshCoordinate the volume and diag^3 overflow: coordinates_too_large says so, and a "flat" or "inward"
  // read from infinities would be false.
  if (measurable && facts.non_finite.empty() && facts.too_large.empty()) {
    const std::string capped_text = capped ? " with its holes capped" : "";
    // Components that enclose a volume, by the sign of their volume. A model of separate bodies with some of them
    // flipped sums to about nothing (equal bodies) or to a negative volume (the largest flipped): "flat" or
    // "flip every face" would be wrong advice there (the latter flips the good bodies). Inward components inside
    // an outward one (cavity walls) keep the total positive and only warn, below.
    // A whole hollow model flipped (its outer surface inward, its cavity wall outward inside it) is one flip, not
    // components to name: an outward component inside an inward one's box keeps the whole-flip advice.
    const Eigen::Matrix<double, Eigen::Dynamic, 6> box = group_boxes(m.V, F, facts.component_of_face, facts.components);
    std::vector<int> inward, outward;
    for (int c = 0; c < facts.components; ++c) {
      const double own = (box.row(c).tail<3>() - box.row(c).head<3>()).norm();  // flat by its own size
      if (std::abs(component_volume[c]) > kFlatVolumeRatio * own * own * own)
        (component_volume[c] < 0 ? inward : outward).push_back(c);
    }
    const auto inside = [&](int c, int around) {
      return (box.row(around).head<3>().array() <= box.row(c).head<3>().array()).all() &&
             (box.row(c).tail<3>().array() <= box.row(around).tail<3>().array()).all();
    };
    const bool cavity_flipped = std::any_of(outward.begin(), outward.end(), [&](int c) {
      return std::any_of(inward.begin(), inward.end(), [&](int k) { return inside(c, k); });
    });
    const bool not_positive = !(volume > kFlatVolumeRatio * diag * diag * diag);
    if (not_positive && !inward.empty() && !outward.empty() && !cavity_flipped) {
      out.error("inward", plural(inward.size(), "component") + " oriented inward (negative volume; first: component " +
                              first_few(inward) + ") beside " + plural(outward.size(), "component") +
                              " oriented outward, summing to " + number(volume) + capped_text +
                              ": flip the faces of the inward components (swap two indices of each of their faces)");
    } else if (std::abs(volume) <= kFlatVolumeRatio * diag * diag * diag) {
      out.error("flat", "the mesh encloses no volume (signed volume " + number(volume) + capped_text +
                            " for a bounding-box diagonal of " + number(diag) +
                            "): a flat or folded surface has no inside to keep");
    } else if (volume < 0) {
      out.error("inward", "the faces are oriented inward (signed volume " + number(volume) + capped_text +
                              " < 0); flipping every face (swapping two of its indices) fixes it");
    } else {
      std::vector<int> negative;  // every one, flat or not (the lists above leave flat ones out)
      for (int c = 0; c < facts.components; ++c)
        if (component_volume[c] < 0) negative.push_back(c);
      if (!negative.empty())
        out.warning("component_inward", plural(negative.size(), "component") +
                                            " with negative volume (first: component " + first_few(negative) +
                                            "): either inner cavity walls or flipped parts");
    }
  }
  if (measurable && facts.components == 1) {
    const int chi = (facts.nv - static_cast<int>(facts.unreferenced.size())) - s.edges + facts.nf;
    const int twice_genus = 2 - chi - s.holes;
    if (twice_genus % 2 == 0 && twice_genus >= 0) s.genus = twice_genus / 2;
  }
}

}  // namespace

bool CheckReport::ok() const {
  return std::none_of(findings.begin(), findings.end(), [](const Finding& f) { return f.severity == Severity::Error; });
}

std::string CheckReport::text() const {
  std::string out;
  for (Severity s : {Severity::Error, Severity::Warning, Severity::Note})
    for (const Finding& f : findings)
      if (f.severity == s)
        out += std::string(s == Severity::Error     ? "error: "
                           : s == Severity::Warning ? "warning: "
                                                    : "note: ") +
               f.message + "\n";
  return out;
}

CheckReport check_mesh(const Mesh& m, const std::string& role, const CheckOptions& options) {
  CheckReport report;
  Reporter out(&report, role, options.names);
  MeshSummary& s = report.summary;
  Facts facts;
  facts.nv = static_cast<int>(m.V.rows());
  facts.nf = static_cast<int>(m.F.rows());
  s.vertices = facts.nv;
  s.faces = facts.nf;
  if (facts.nf == 0) out.error("no_faces", "the mesh has no faces (" + plural(facts.nv, "vertex") + ")");
  check_coordinates(m, out, s, facts);
  check_faces(m, out, facts);
  check_duplicates(m, out, facts);
  check_edges(m, out, s, facts, options.model_rules);
  check_unreferenced(out, facts);
  check_components(m, out, s, facts, options.model_rules, role);
  check_volume_and_genus(m, out, s, facts, options.model_rules);
  return report;
}

namespace {

// The cage's face boxes grown by the surface tolerance: most faces are far from a given point, and a
// box test rejects them before the point-triangle distance.
struct FaceBoxes {
  std::vector<double> lo_x, lo_y, lo_z, hi_x, hi_y, hi_z;
};

FaceBoxes face_boxes(const Mesh& cage, double tolerance) {
  FaceBoxes boxes;
  for (Eigen::Index f = 0; f < cage.F.rows(); ++f) {
    const Eigen::RowVector3d a = cage.V.row(cage.F(f, 0)), b = cage.V.row(cage.F(f, 1)), c = cage.V.row(cage.F(f, 2));
    const Eigen::RowVector3d lo = a.cwiseMin(b).cwiseMin(c).array() - tolerance;
    const Eigen::RowVector3d hi = a.cwiseMax(b).cwiseMax(c).array() + tolerance;
    boxes.lo_x.push_back(lo.x()), boxes.lo_y.push_back(lo.y()), boxes.lo_z.push_back(lo.z());
    boxes.hi_x.push_back(hi.x()), boxes.hi_y.push_back(hi.y()), boxes.hi_z.push_back(hi.z());
  }
  return boxes;
}

bool near_surface(const Mesh& cage, const FaceBoxes& boxes, const Eigen::RowVector3d& p, double tolerance) {
  const double t2 = tolerance * tolerance;
  for (size_t i = 0; i < boxes.lo_x.size(); ++i) {
    if (p.x() < boxes.lo_x[i] || p.x() > boxes.hi_x[i] || p.y() < boxes.lo_y[i] || p.y() > boxes.hi_y[i] ||
        p.z() < boxes.lo_z[i] || p.z() > boxes.hi_z[i])
      continue;
    const auto f = static_cast<Eigen::Index>(i);
    if (point_triangle_squared_distance(p.transpose(), cage.V.row(cage.F(f, 0)).transpose(),
                                        cage.V.row(cage.F(f, 1)).transpose(),
                                        cage.V.row(cage.F(f, 2)).transpose()) <= t2)
      return true;
  }
  return false;
}

}  // namespace

namespace {

// What the layout did to the file's mesh, said in its own numbers (the summary then counts the file's
// vertices and faces).
void add_layout_notes(CheckReport& report, const MeshLayout& layout) {
  const LayoutStats& l = layout.stats();
  MeshSummary& s = report.summary;
  s.layout = l;
  s.vertices = l.file_vertices;
  s.faces = l.file_faces;
  Reporter out(&report, "mesh", nullptr);
  if (layout.identity()) return;
  if (l.welded > 0)
    out.note("welded", plural(static_cast<size_t>(l.welded), "vertex") +
                           " at the same point as another (within 1e-6 of the "
                           "bounding-box diagonal) welded: " +
                           std::to_string(l.file_vertices - l.unreferenced) + " vertices in the file, " +
                           std::to_string(l.solver_vertices - l.split_vertices) +
                           " points for the solver; the file's own vertices are "
                           "kept for display and export");
  if (l.collapsed_faces > 0)
    out.note("collapsed_faces",
             plural(static_cast<size_t>(l.collapsed_faces), "face") +
                 " whose corners are one point "
                 "(welded or repeated) left out of the solver: they have no area to deform; they stay in the file");
  if (l.split_vertices > 0)
    out.note("split_vertices",
             "non-manifold vertices or edges split: " + plural(static_cast<size_t>(l.split_vertices), "vertex") +
                 " added, so that each fan of faces (" + std::to_string(l.paired_edges) +
                 " edges with more than two faces paired "
                 "by angle) deforms as its own surface; the copies are one vertex again in the file");
  if (l.unreferenced > 0) {
    std::vector<int> list;
    for (int v = 0; v < l.file_vertices && list.size() <= kShown; ++v)
      if (layout.solver_of_file()[v] < 0) list.push_back(v);
    out.warning("unreferenced_vertices", plural(static_cast<size_t>(l.unreferenced), "vertex") +
                                             " used by no face (first: " + first_few(list) +
                                             "); they are carried along with the nearest triangle");
  }
}

// The cage's own findings, then (when the cage can be evaluated) self-intersection and where each mesh
// vertex lies: added to the mesh's report.
void add_cage_findings(CheckReport& report, const Mesh& mesh, const Mesh& cage, const IndexNames* names) {
  const CheckReport cage_report = check_mesh(cage, "cage");
  report.findings.insert(report.findings.end(), cage_report.findings.begin(), cage_report.findings.end());

  // The inside test needs a cage whose faces and coordinates can be evaluated at all: beyond kMaxMeshCoordinate
  // the solid angles overflow, and every vertex would be reported outside (the cage's own finding says why).
  const int cage_vertices = static_cast<int>(cage.V.rows());
  if (cage.F.rows() == 0 || !cage.V.allFinite() || cage.V.cwiseAbs().maxCoeff() > kMaxMeshCoordinate ||
      (cage.F.array() < 0).any() || (cage.F.array() >= cage_vertices).any())
    return;
  const double tolerance = kOnSurfaceRatio * bounding_box_diagonal(cage.V);
  // Mean value coordinates are meaningless inside a cage that crosses itself.
  if (cage_report.ok()) {
    // Only true crossings: a sharp but valid crease (two faces 0.4 degrees apart on the armadillo's cage)
    // is not one.
    const auto crossings = self_intersections(cage, tolerance, kMaxCrossingsListed, kFoldedFlatCos);
    if (!crossings.empty())
      report.findings.push_back(
          {Severity::Error, "self_intersecting",
           "cage: " + std::string(crossings.size() >= size_t(kMaxCrossingsListed) ? "at least " : "") +
               plural(crossings.size(), "pair") + " of faces intersect (first: " +
               first_few(crossings,
                         [](const std::pair<int, int>& c) {
                           return "faces " + std::to_string(c.first) + " and " + std::to_string(c.second);
                         }) +
               "); a cage must not cross itself"});
  }
  const FaceBoxes boxes = face_boxes(cage, tolerance);
  const BatchWindingNumber winding(cage);
  // One winding number per vertex, independent: blocks of vertices on the thread pool, each with its own
  // scratch; the lists are then collected in vertex order (the same with any thread count).
  enum Where : unsigned char { kInside, kOnSurface, kOutside, kNotFinite };
  std::vector<unsigned char> where(static_cast<size_t>(mesh.V.rows()), kInside);
  parallel::parallel_for(0, static_cast<int>(mesh.V.rows()), 256, [&](int lo, int hi) {
    BatchWindingNumber::Scratch scratch;
    for (int i = lo; i < hi; ++i) {
      const Eigen::RowVector3d p = mesh.V.row(i);
      if (!p.allFinite()) where[i] = kNotFinite;  // already reported as non-finite
      else if (near_surface(cage, boxes, p, tolerance)) where[i] = kOnSurface;
      else if (!(winding(p, scratch) > 0.5)) where[i] = kOutside;
    }
  });
  std::vector<int> outside, on_surface;
  int tested = 0;
  for (int i = 0; i < mesh.V.rows(); ++i) {
    const int name = names ? names->vertex[i] : i;  // the file's number
    if (where[i] != kNotFinite) ++tested;
    if (where[i] == kOnSurface) on_surface.push_back(name);
    if (where[i] == kOutside) outside.push_back(name);
  }
  const std::string of = " of " + std::to_string(tested) + " mesh vertices ";
  if (!outside.empty())
    report.findings.push_back({Severity::Error, "outside_cage",
                               std::to_string(outside.size()) + of + (outside.size() == 1 ? "is" : "are") +
                                   " outside the cage (first: " + first_few(outside) + ")"});
  if (!on_surface.empty())
    report.findings.push_back({Severity::Error, "on_cage",
                               std::to_string(on_surface.size()) + of + (on_surface.size() == 1 ? "lies" : "lie") +
                                   " on the cage surface (within 1e-9 x cage bbox diagonal; first: " +
                                   first_few(on_surface) + "); they must be strictly inside"});
}

}  // namespace

CheckReport check_mesh_in_cage(const Mesh& mesh, const Mesh& cage, const CheckOptions& mesh_options) {
  CheckReport report = check_mesh(mesh, "mesh", mesh_options);
  add_cage_findings(report, mesh, cage, mesh_options.names);
  return report;
}

CheckReport check_model(const MeshLayout& layout) {
  const IndexNames names = layout.names();
  CheckOptions options;
  options.model_rules = true;
  options.names = &names;
  CheckReport report = check_mesh(layout.mesh(), "mesh", options);
  add_layout_notes(report, layout);
  return report;
}

CheckReport check_model(const Mesh& mesh, const LayoutOptions& options) {
  return check_model(MeshLayout(mesh, options));
}

CheckReport check_model_in_cage(const MeshLayout& layout, const Mesh& cage) {
  CheckReport report = check_model(layout);
  const IndexNames names = layout.names();
  add_cage_findings(report, layout.mesh(), cage, &names);
  return report;
}

namespace {

// MeshOutsideCage when every error is about where the mesh sits in the cage (the meshes themselves are
// fine: a bigger or moved cage fixes it); InvalidMesh otherwise.
ErrorCode code_of(const std::vector<Finding>& findings) {
  bool placement = false;
  for (const Finding& f : findings) {
    if (f.severity != Severity::Error) continue;
    if (f.code != "outside_cage" && f.code != "on_cage") return ErrorCode::InvalidMesh;
    placement = true;
  }
  return placement ? ErrorCode::MeshOutsideCage : ErrorCode::InvalidMesh;
}

}  // namespace

MeshError::MeshError(const CheckReport& report, const std::string& context)
    : Error(code_of(report.findings), context + report.text()), findings_(report.findings) {}

void throw_if_invalid(const CheckReport& report) {
  if (!report.ok()) throw MeshError(report);
}

}  // namespace sd
