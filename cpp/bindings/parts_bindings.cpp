// Volume parts for JS (docs/method.md section 16): a partition of the triangles made from a scene's lists or
// automatically. Wrapped by web/lib/parts.js; the Deformer takes the result (setVolumeParts).
//   volumePartsFromLists(indices, vertexCount, lists, 'vertices' | 'triangles') -> Int32Array, part per triangle
//   autoVolumeParts(positions, indices, parts) -> Int32Array (spectral clustering, auto_partition.h, on the
//   model's welded mesh)
#include <emscripten/bind.h>

#include <climits>
#include <string>
#include <vector>

#include "bindings/convert.h"
#include "core/parts/auto_partition.h"
#include "core/parts/partition.h"

namespace sd::bindings {
namespace {

val parts_from_lists(const val& indices, const val& vertex_count, const val& lists, const std::string& kind) {
  return guarded([&] {
    const Faces F = faces_from_js(indices, "volumeParts: indices");
    const int n = integer_in(vertex_count, "volumeParts: vertexCount", 0, INT_MAX);
    if (!present(lists) || !present(lists["length"])) throw Error("volumeParts: the lists must be an array of arrays");
    std::vector<std::vector<int>> out;
    const unsigned count = lists["length"].as<unsigned>();
    for (unsigned j = 0; j < count; ++j)
      out.push_back(ints_from_js(lists[j], "volumeParts: list " + std::to_string(j) + ", entry", 0, INT_MAX));
    if (kind == "vertices") return to_js(parts_from_vertex_lists(out, F, n));
    if (kind == "triangles") return to_js(parts_from_triangle_lists(out, static_cast<int>(F.rows())));
    throw Error("volumeParts: lists are of 'vertices' or 'triangles' (got '" + kind + "')");
  });
}

val auto_parts_js(const val& positions, const val& indices, const val& parts) {
  return guarded([&] {
    // On the welded solver mesh (a seam would cut the spectral embedding apart), returned per file triangle.
    const MeshLayout layout(mesh_from_js(positions, indices, "mesh"));
    throw_if_invalid(check_model(layout));
    return to_js(layout.file_face_parts(auto_parts(layout.mesh(), integer_in(parts, "volumeParts: auto", 1, INT_MAX))));
  });
}

}  // namespace
}  // namespace sd::bindings

EMSCRIPTEN_BINDINGS(parts) {
  using namespace sd::bindings;
  emscripten::function("volumePartsFromLists", &parts_from_lists);
  emscripten::function("autoVolumeParts", &auto_parts_js);
}
