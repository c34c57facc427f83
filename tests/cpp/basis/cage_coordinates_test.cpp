#include "core/basis/cage_coordinates.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "test_support.h"
#include "basis/cage_fixtures.h"

namespace sd {
namespace {

TEST(CageCoordinates, NamesRoundTrip) {
  ASSERT_EQ(all_coordinate_types().size(), 3u);
  EXPECT_EQ(all_coordinate_types().front(), CoordinateType::MeanValue);  // the default first
  for (CoordinateType type : all_coordinate_types()) {
    EXPECT_TRUE(test::is_snake_case(coordinate_type_name(type)));
    EXPECT_EQ(coordinate_type_from_name(coordinate_type_name(type)), type);
  }
  test::expect_error([] { coordinate_type_from_name("green"); }, "coordinates must be one of 'mvc', 'pmvc', 'harmonic'",
                     ErrorCode::InvalidArgument);
}

// Each type binds through the one entry point exactly as through its own function, and says which it was.
TEST(CageCoordinates, DispatchesToEachType) {
  const test::BentBar bent = test::bent_bar();
  CoordinatesOptions options;
  options.positive.resolution = 8;
  options.harmonic.resolution = 16;
  MvcOptions binding;
  for (CoordinateType type : all_coordinate_types()) {
    options.type = type;
    CoordinatesReport report;
    const Eigen::MatrixXd W = cage_coordinates(bent.mesh.V, bent.cage, binding, options, &report).to_dense();
    Eigen::MatrixXd expected;
    if (type == CoordinateType::MeanValue)
      expected = mean_value_coordinates(bent.mesh.V, bent.cage, binding).to_dense();
    if (type == CoordinateType::PositiveMeanValue)
      expected = positive_mean_value_coordinates(bent.mesh.V, bent.cage, binding, options.positive).to_dense();
    if (type == CoordinateType::Harmonic)
      expected = harmonic_coordinates(bent.mesh.V, bent.cage, binding, options.harmonic).to_dense();
    EXPECT_EQ((W - expected).cwiseAbs().maxCoeff(), 0.0) << coordinate_type_name(type);
    EXPECT_EQ(report.type, type);
    EXPECT_EQ(report.binding.min_weight, W.minCoeff());
    EXPECT_EQ(report.positive.rays > 0, type == CoordinateType::PositiveMeanValue);
    EXPECT_EQ(report.harmonic.resolution, type == CoordinateType::Harmonic ? 16 : 0);
  }
}

}  // namespace
}  // namespace sd
