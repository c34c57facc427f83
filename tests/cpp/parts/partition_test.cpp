#include "core/parts/partition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>

#include "core/mesh/shapes.h"
#include "test_support.h"

namespace sd {
namespace {

using test::expect_error;

TEST(Partition, TriangleListsWithTheRestAsTheLastPart) {
  const std::vector<int> parts = parts_from_triangle_lists({{0, 1}, {5}}, 7);
  EXPECT_EQ(parts, (std::vector<int>{0, 0, 2, 2, 2, 1, 2}));
  EXPECT_EQ(validate_parts(parts, 7), 3);
  EXPECT_EQ(parts_from_triangle_lists({{0, 1, 2}}, 3), (std::vector<int>{0, 0, 0})) << "nothing left: no rest";
}

TEST(Partition, VertexListsGiveEachTriangleToTheMajorityOfItsVertices) {
  Faces F(4, 3);
  F << 0, 1, 2,  // all in list 0
      1, 2, 3,   // two in list 0, one in list 1 -> 0
      3, 4, 5,   // list 1, list 1, rest -> 1
      2, 4, 6;   // list 0, list 1, rest -> the lowest, 0
  const std::vector<int> parts = parts_from_vertex_lists({{0, 1, 2}, {3, 4}}, F, 7);
  EXPECT_EQ(parts, (std::vector<int>{0, 0, 1, 0}));
}

TEST(Partition, ConnectPartsMergesStrayPiecesIntoTheirNeighbourAndCompactRenumbers) {
  // make_box(1, 1, 1, 1): triangles 0-1 are the face z = -1/2, 2-3 the face z = +1/2, 4-11 the four sides.
  // Part 0 = both z faces (two pieces, opposite each other), part 1 = the sides.
  const Mesh box = make_box(1, 1, 1, 1);
  std::vector<int> part{0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1};
  connect_parts(part, box.F);
  const int zeros = static_cast<int>(std::count(part.begin(), part.end(), 0));
  EXPECT_EQ(zeros, 2) << "one z face stays in part 0, the other joins the sides it touches";
  EXPECT_EQ(part[0], part[1]);
  EXPECT_EQ(part[2], part[3]);
  EXPECT_NE(part[0], part[2]);
  std::vector<int> connected{0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  const std::vector<int> unchanged = connected;
  connect_parts(connected, box.F);
  EXPECT_EQ(connected, unchanged) << "connected parts are left alone";
  std::vector<int> gaps{3, 3, 7, 7, 3};
  compact_parts(gaps);
  EXPECT_EQ(gaps, (std::vector<int>{0, 0, 1, 1, 0}));
}

TEST(Partition, RefusesOverlapsBadIndicesEmptyListsAndGaps) {
  const Mesh box = make_box(1, 1, 1, 1);  // 8 vertices, 12 triangles
  const int n = 8, f = 12;
  expect_error([&] { parts_from_triangle_lists({{0, 1}, {1}}, f); }, "triangle 1 is in list 0 and list 1");
  expect_error([&] { parts_from_triangle_lists({{0, 12}}, f); }, "list 0 has triangle 12 outside [0, 12)");
  expect_error([&] { parts_from_triangle_lists({{0}, {}}, f); }, "list 1 is empty");
  expect_error(
      [&] {
        parts_from_vertex_lists({{0}, {1, 2, 3, 4, 5, 6, 7}}, box.F, n);
      },
      "vertex list 0 holds no triangle");
  expect_error([&] { parts_from_vertex_lists({{-1}}, box.F, n); }, "list 0 has vertex -1 outside [0, 8)");
  expect_error([&] { validate_parts({0, 0, 2}, 3); }, "part 1 has no triangle");
  expect_error([&] { validate_parts({0, 0}, 3); }, "2 part indices for 3 triangles");
  expect_error([&] { validate_parts({0, -1, 0}, 3); }, "triangle 1 has part -1");
}

// One part per triangle of a 10k-triangle mesh ran a minute and took gigabytes before failing; the count is
// checked before any work (and before a part index near INT_MAX could size a table).
TEST(Partition, RefusesMoreThanTheMostPartsBeforeAnyWork) {
  const int faces = 2 * kMaxVolumeParts + 10;
  std::vector<std::vector<int>> one_per_triangle;
  for (int t = 0; t < faces; ++t) one_per_triangle.push_back({t});
  expect_error([&] { parts_from_triangle_lists(one_per_triangle, faces); },
               "the lists make " + std::to_string(faces) + " parts, more than the " + std::to_string(kMaxVolumeParts));
  const std::vector<std::vector<int>> most(one_per_triangle.begin(), one_per_triangle.begin() + kMaxVolumeParts);
  expect_error([&] { parts_from_triangle_lists(most, faces); },
               "the lists and the unlisted rest make " + std::to_string(kMaxVolumeParts + 1) + " parts");
  EXPECT_EQ(validate_parts(parts_from_triangle_lists(most, kMaxVolumeParts), kMaxVolumeParts), kMaxVolumeParts);
  std::vector<int> each(static_cast<size_t>(faces));
  for (int t = 0; t < faces; ++t) each[t] = t;
  expect_error([&] { validate_parts(each, faces); }, "the part indices ask for " + std::to_string(faces) + " parts");
  expect_error([&] { validate_parts({0, INT_MAX}, 2); }, "ask for 2147483648 parts");
}

}  // namespace
}  // namespace sd
