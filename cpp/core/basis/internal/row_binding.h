// The parallel row loop shared by the coordinates computed one point at a time (mean value and positive
// mean value coordinates): blocks of rows on the thread pool, each with its own evaluator (scratch memory),
// findings (smallest weight, on-vertex and on-face counts, points outside the cage) combined in block order
// so W and the report do not depend on the thread count, progress reported and cancellation honoured on the
// calling thread between chunks (the callback may be a JS function, which a pool thread cannot call).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/basis/internal/mean_value_integrals.h"
#include "core/basis/mean_value_coordinates.h"
#include "core/basis/basis_matrix.h"

namespace sd {

// Writes the normalised row of point i into row (length m) and its kind; returns false when the point is
// outside the cage.
class RowEvaluator {
 public:
  virtual ~RowEvaluator() = default;
  virtual bool evaluate(int i, double* row, PointKind& kind) = 0;
  // Counts of the evaluator's own (rays cast, ...), summed over all rows in block order by bind_rows.
  virtual std::vector<double> tallies() const { return {}; }
};

// W (#points by m). Throws sd::Error: MeshOutsideCage naming how many points are outside and the first few
// (the message starts with `what`), Cancelled when the progress callback returns false. Fills report's
// min_weight (and where), on_vertex and on_face; `tallies`, when given, the sums of the evaluators' tallies.
BasisMatrix bind_rows(const Vertices& points, int m, const MvcOptions& options, const std::string& what,
                      const std::function<std::unique_ptr<RowEvaluator>()>& make_evaluator, MvcReport& report,
                      std::vector<double>* tallies = nullptr);

// Throws sd::Error (InvalidMesh) naming the first point with a non-finite coordinate.
void check_points_finite(const Vertices& points, const std::string& what);

}  // namespace sd
