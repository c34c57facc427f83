#include "core/basis/cage_coordinates.h"

#include "core/error.h"

namespace sd {

const char* coordinate_type_name(CoordinateType type) {
  switch (type) {
    case CoordinateType::MeanValue: return "mvc";
    case CoordinateType::PositiveMeanValue: return "pmvc";
    case CoordinateType::Harmonic: return "harmonic";
  }
  return "mvc";
}

const std::vector<CoordinateType>& all_coordinate_types() {
  static const std::vector<CoordinateType> types = {CoordinateType::MeanValue, CoordinateType::PositiveMeanValue,
                                                    CoordinateType::Harmonic};
  return types;
}

CoordinateType coordinate_type_from_name(const std::string& name) {
  std::string known;
  for (CoordinateType type : all_coordinate_types()) {
    if (name == coordinate_type_name(type)) return type;
    known += (known.empty() ? "'" : ", '") + std::string(coordinate_type_name(type)) + "'";
  }
  throw Error("coordinates must be one of " + known + " (got '" + name + "')");
}

BasisMatrix cage_coordinates(const Vertices& points, const Mesh& cage, const MvcOptions& binding,
                             const CoordinatesOptions& options, CoordinatesReport* report) {
  CoordinatesReport local;
  local.type = options.type;
  BasisMatrix W;
  switch (options.type) {
    case CoordinateType::MeanValue: W = mean_value_coordinates(points, cage, binding, &local.binding); break;
    case CoordinateType::PositiveMeanValue:
      W = positive_mean_value_coordinates(points, cage, binding, options.positive, &local.binding, &local.positive);
      break;
    case CoordinateType::Harmonic:
      W = harmonic_coordinates(points, cage, binding, options.harmonic, &local.binding, &local.harmonic);
      break;
  }
  if (report) *report = local;
  return W;
}

}  // namespace sd
