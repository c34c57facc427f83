// The cage coordinates W (X = W P) a cage basis binds, by type:
//   mvc       mean value coordinates (mean_value_coordinates.h; the default): smooth, linear precision, negative
//             inside concave cages
//   pmvc      positive mean value coordinates (positive_mean_value_coordinates.h): >= 0, no linear precision where
//             a point does not see the whole cage
//   harmonic  harmonic coordinates (harmonic_coordinates.h): >= 0, smooth, linear precision to the grid's
//             resolution, a grid solve per binding
// Every type gives a dense n x m BasisMatrix whose rows sum to 1, so the solver uses each the same way.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/basis/harmonic_coordinates.h"
#include "core/basis/mean_value_coordinates.h"
#include "core/basis/positive_mean_value_coordinates.h"
#include "core/basis/basis_matrix.h"

namespace sd {

enum class CoordinateType { MeanValue, PositiveMeanValue, Harmonic };

// "mvc", "pmvc", "harmonic": the spelling of scenes, JS and the CLI.
const char* coordinate_type_name(CoordinateType type);
// Every type, the default first.
const std::vector<CoordinateType>& all_coordinate_types();
// Throws sd::Error (InvalidArgument) naming the valid names.
CoordinateType coordinate_type_from_name(const std::string& name);

struct CoordinatesOptions {
  CoordinateType type = CoordinateType::MeanValue;
  PositiveMvcOptions positive;  // pmvc only
  HarmonicOptions harmonic;     // harmonic only
};

struct CoordinatesReport {
  CoordinateType type = CoordinateType::MeanValue;
  MvcReport binding;           // smallest weight and where, counts, seconds (every type)
  PositiveMvcReport positive;  // pmvc: the rays cast
  HarmonicReport harmonic;     // harmonic: the grid, the factor, the resolution used
};

// Throws sd::Error as the chosen type's function does.
BasisMatrix cage_coordinates(const Vertices& points, const Mesh& cage, const MvcOptions& binding,
                             const CoordinatesOptions& options, CoordinatesReport* report = nullptr);

}  // namespace sd
