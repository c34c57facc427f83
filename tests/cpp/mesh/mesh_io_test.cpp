#include "core/mesh/mesh_io.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "test_support.h"

// Every operator new of this test program goes through here, so a test can see the largest single allocation
// made while it watches (std::vector, which the readers fill, allocates with it).
namespace {
std::atomic<bool> watching_allocations{false};
std::atomic<size_t> largest_allocation{0};
}  // namespace

void* operator new(std::size_t size) {
  if (watching_allocations.load(std::memory_order_relaxed)) {
    size_t seen = largest_allocation.load(std::memory_order_relaxed);
    while (size > seen && !largest_allocation.compare_exchange_weak(seen, size)) {
    }
  }
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace sd {
namespace {

// The largest allocation between its construction and largest().
class AllocationWatch {
 public:
  AllocationWatch() {
    largest_allocation = 0;
    watching_allocations = true;
  }
  ~AllocationWatch() { watching_allocations = false; }
  size_t largest() const { return largest_allocation; }
};

using Reader = Mesh (*)(std::string_view);
const std::vector<std::pair<const char*, Reader>> kReaders = {
    {"obj", read_obj}, {"off", read_off}, {"ply", read_ply}, {"stl", read_stl}};

std::string test_file(const std::string& name) { return test::read_file(std::string(SD_TEST_DATA_DIR) + "/" + name); }

// The message of the sd::Error that `parse` throws ("" and a test failure when it does not throw).
std::string error_of(const std::function<void()>& parse) {
  try {
    parse();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an sd::Error";
  return "";
}

// Unit cube [0,1]^3: 8 corners, 12 triangles after fan triangulation of its 6 quads.
void expect_unit_cube(const Mesh& m) {
  ASSERT_EQ(m.V.rows(), 8);
  ASSERT_EQ(m.F.rows(), 12);
  EXPECT_EQ(m.V.colwise().minCoeff(), Eigen::RowVector3d(0, 0, 0));
  EXPECT_EQ(m.V.colwise().maxCoeff(), Eigen::RowVector3d(1, 1, 1));
  double volume6 = 0;  // 6 x volume: exact in floating point for these coordinates
  for (int f = 0; f < 12; ++f) volume6 += m.V.row(m.F(f, 0)).dot(m.V.row(m.F(f, 1)).cross(m.V.row(m.F(f, 2))));
  EXPECT_EQ(volume6, 6.0);
}

// The tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1), outward: volume exactly 1/6.
void expect_unit_tetra(const Mesh& m) {
  ASSERT_EQ(m.V.rows(), 4);
  ASSERT_EQ(m.F.rows(), 4);
  EXPECT_EQ(m.V.rowwise().sum().sum(), 3.0);
  double volume = 0;
  for (int f = 0; f < 4; ++f) volume += m.V.row(m.F(f, 0)).dot(m.V.row(m.F(f, 1)).cross(m.V.row(m.F(f, 2))));
  EXPECT_EQ(volume, 1.0);  // 6 x volume
}

// ----- OBJ

TEST(MeshIo, ObjRoundTripIsBitExact) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Mesh m;
  m.V.resize(50, 3);
  for (int i = 0; i < 50; ++i)
    for (int a = 0; a < 3; ++a) m.V(i, a) = uniform(rng) * std::pow(10.0, static_cast<int>(rng() % 40) - 20);
  m.V(0, 0) = -0.0;
  m.V(1, 1) = std::numeric_limits<double>::denorm_min();
  m.V(2, 2) = std::numeric_limits<double>::max();
  m.V(3, 0) = 0.1;
  m.F.resize(40, 3);
  for (int f = 0; f < 40; ++f) m.F.row(f) << f, f + 1, f + 2;
  const Mesh back = read_obj(write_obj(m, "line one\nline two"));
  ASSERT_EQ(back.V.rows(), 50);
  EXPECT_EQ(std::memcmp(back.V.data(), m.V.data(), sizeof(double) * 150), 0);
  EXPECT_EQ(back.F, m.F);
  EXPECT_EQ(write_obj(m, "line one\nline two").rfind("# line one\n# line two\nv ", 0), 0u);
}

// "v nan 0 0" is no OBJ this reader (or any) takes back.
TEST(MeshIo, WriteObjRefusesNonFiniteCoordinatesNamingTheVertex) {
  Mesh m{Vertices(3, 3), Faces(1, 3)};
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  m.F << 0, 1, 2;
  m.V(1, 2) = std::nan("");
  test::expect_error([&] { write_obj(m); }, "vertex 1 has a NaN or infinite coordinate", ErrorCode::InvalidArgument);
  m.V(1, 2) = -std::numeric_limits<double>::infinity();
  test::expect_error([&] { write_obj(m); }, "vertex 1 has a NaN or infinite coordinate");
}

TEST(MeshIo, ObjReadsQuadsWithSlashesCommentsAndNegativeIndices) {
  expect_unit_cube(read_obj(test_file("cube_quads.obj")));
}

TEST(MeshIo, ObjFanTriangulatesPolygons) {
  const Mesh m = read_obj("v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n");
  Faces expected(3, 3);
  expected << 0, 1, 2, 0, 2, 3, 0, 3, 4;
  EXPECT_EQ(m.F, expected);
}

TEST(MeshIo, ObjNegativeIndicesCountFromTheLastVertexSoFar) {
  const Mesh m = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf -4/1 -2/2/2 -1//3\n");
  Faces expected(2, 3);
  expected << 0, 1, 2, 0, 2, 3;
  EXPECT_EQ(m.F, expected);
}

TEST(MeshIo, ObjAcceptsFacesBeforeTheirVerticesAndCrLf) {
  const Mesh m = read_obj("f 1 2 3\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\n");
  EXPECT_EQ(m.F.rows(), 1);
  EXPECT_EQ(m.V(1, 0), 1.0);
}

TEST(MeshIo, ObjErrorsNameTheLine) {
  EXPECT_NE(error_of([] { read_obj(test_file("bad_index.obj")); }).find("OBJ line 5: face index 9 is out of range"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_obj("v 0 0 0\nv 1 0 0\nf 1 2\n"); }).find("OBJ line 3: face has 2 vertices"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_obj("v 0 0 0\nv 1 x 0\n"); }).find("OBJ line 2: vertex coordinate 'x' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"); }).find("OBJ line 4: face index 0"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_obj("v 0 0 0\nf -2 -1 1\n"); }).find("OBJ line 2: face index -2 is out of range"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_obj("v 0 0\n"); }).find("OBJ line 1: vertex needs 3 coordinates"), std::string::npos);
  EXPECT_NE(error_of([] {
              read_obj(
                  "\x7f"
                  "ELF\x02\x01\n");
            }).find("OBJ line 1: unknown keyword"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_obj("# nothing\nv 0 0 0\n"); }).find("OBJ: the file has no faces (1 vertices)"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_obj(""); }).find("no faces"), std::string::npos);
}

TEST(MeshIo, ObjParsesNonFiniteCoordinatesForTheChecker) {
  const Mesh m = read_obj(test_file("nan_tetra.obj"));
  EXPECT_TRUE(std::isnan(m.V(0, 0)));
  EXPECT_EQ(read_obj("v inf -inf 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").V(0, 1), -std::numeric_limits<double>::infinity());
}

// ----- OFF

TEST(MeshIo, OffReadsTetraAndColouredQuadCube) {
  expect_unit_tetra(read_off(test_file("tetra.off")));
  expect_unit_cube(read_off(test_file("cube.off")));
}

TEST(MeshIo, OffErrorsNameTheLine) {
  EXPECT_NE(
      error_of([] { read_off(test_file("truncated.off")); }).find("OFF line 6: the file ends after 3 of 4 vertices"),
      std::string::npos);
  EXPECT_NE(error_of([] {
              read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
            }).find("OFF line 6: face index 3 is out of range (3 vertices)"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"); }).find("OFF line 6: face has 2"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n5 0 1 2\n");
            }).find("face declares 5 vertices but the line has 3 indices"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_off("OFF\n3 1 0\n0 0 0\n1 0 zero\n"); }).find("OFF line 4: vertex coordinate 'zero'"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_off("PLY\n"); }).find("OFF line 1: expected the header 'OFF'"), std::string::npos);
  EXPECT_NE(error_of([] { read_off("4OFF\n"); }).find("unsupported OFF variant"), std::string::npos);
  EXPECT_NE(error_of([] { read_off("OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"); }).find("OFF: the file has no faces"),
            std::string::npos);
}

TEST(MeshIo, HugeDeclaredCountsAreRejectedWithoutAllocating) {
  const AllocationWatch watch;
  EXPECT_NE(error_of([] {
              read_off(test_file("huge_counts.off"));
            }).find("OFF line 4: the file ends after 1 of 2000000000 vertices"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_ply(test_file("huge_counts.ply")); }).find("only 4 bytes follow the header"),
            std::string::npos);
  // Binary STL declaring 2^32-1 triangles in 84 bytes.
  std::string stl(84, '\0');
  std::memset(&stl[80], 0xff, 4);
  EXPECT_NE(error_of([&] { read_stl(stl); }).find("STL (binary) byte offset 80: declares 4294967295 triangles"),
            std::string::npos);
  // A reader that trusted the declared counts would reserve gigabytes (or fail with std::bad_alloc).
  EXPECT_LT(watch.largest(), size_t(1) << 20) << "bytes in one allocation";
}

// ----- PLY

// Binary PLY writer for the tests: appends `value` as type T in the given byte order.
template <class T>
void put(std::string* out, T value, bool big_endian) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  out->append(b, sizeof(T));
}

// The unit cube as binary PLY: double coordinates plus a float "confidence" property, faces as a
// ushort-counted list of uint indices named vertex_index, and an extra list element to skip.
std::string binary_cube_ply(bool big_endian) {
  std::string s = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment test cube\nelement vertex 8\nproperty float confidence\nproperty double x\n"
                  "property double y\nproperty double z\nelement face 6\nproperty uchar flags\n"
                  "property list ushort uint vertex_index\nelement note 1\nproperty list int char text\nend_header\n";
  const int corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& c : corners) {
    put<float>(&s, 0.5f, big_endian);
    for (int a = 0; a < 3; ++a) put<double>(&s, c[a], big_endian);
  }
  const unsigned quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (const auto& q : quads) {
    put<uint8_t>(&s, 7, big_endian);
    put<uint16_t>(&s, 4, big_endian);
    for (unsigned id : q) put<uint32_t>(&s, id, big_endian);
  }
  put<int32_t>(&s, 2, big_endian);
  s += "hi";
  return s;
}

TEST(MeshIo, PlyReadsAsciiAndBothBinaryByteOrders) {
  expect_unit_cube(read_ply(test_file("cube_ascii.ply")));
  const Mesh little = read_ply(binary_cube_ply(false));
  const Mesh big = read_ply(binary_cube_ply(true));
  expect_unit_cube(little);
  expect_unit_cube(big);
  EXPECT_EQ(little.F, big.F);
  EXPECT_EQ(little.F, read_ply(test_file("cube_ascii.ply")).F);
}

TEST(MeshIo, PlyErrorsNameTheLineOrByteOffset) {
  const std::string cube = binary_cube_ply(false);
  const size_t data = cube.find("end_header\n") + 11;
  // Cut inside the 3rd vertex: vertex records are 28 bytes (float + 3 doubles).
  const std::string cut = cube.substr(0, data + 2 * 28 + 10);
  const std::string message = error_of([&] { read_ply(cut); });
  EXPECT_NE(message.find("only 66 bytes follow the header"), std::string::npos) << message;
  // Enough bytes in total but a list count that runs past the end: reported at its byte offset.
  std::string bad = cube;
  const size_t first_face = data + 8 * 28;
  bad[first_face + 2] = '\xff';  // list count 0xff04
  EXPECT_NE(error_of([&] {
              read_ply(bad);
            }).find("PLY (binary_little_endian) byte offset " + std::to_string(first_face + 1) + ": list length 65284"),
            std::string::npos);
  std::string out_of_range = cube;
  out_of_range[first_face + 3] = 8;  // first index of the first face
  EXPECT_NE(error_of([&] {
              read_ply(out_of_range);
            }).find("byte offset " + std::to_string(first_face + 3) + ": face index 8 is out of range (8 vertices)"),
            std::string::npos);
  std::string ascii = test_file("cube_ascii.ply");
  ascii.replace(ascii.find("1 1 1 9"), 7, "1 one 1");
  EXPECT_NE(error_of([&] { read_ply(ascii); }).find("PLY line 21: 'one' is not a number"), std::string::npos);
  EXPECT_NE(error_of([] {
              read_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n");
            }).find("PLY line 4: unknown type 'quad'"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_ply("ply\nformat ascii 1.0\nelement vertex 0\n"); }).find("no 'end_header'"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              read_ply(
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
            }).find("PLY line 13: face has 2 vertices"),
            std::string::npos);
}

// ----- STL

// Binary STL of the unit tetrahedron; the header starts with "solid" as many exporters write.
std::string binary_tetra_stl() {
  std::string s = "solid exported by a tool that writes binary STL anyway";
  s.resize(80, ' ');
  put<uint32_t>(&s, 4, false);
  const float tris[4][3][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}},
                               {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
                               {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                               {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (const auto& t : tris) {
    for (int a = 0; a < 3; ++a) put<float>(&s, 0.0f, false);  // normal (ignored)
    for (const auto& corner : t)
      for (float x : corner) put<float>(&s, x, false);
    put<uint16_t>(&s, 0, false);
  }
  return s;
}

TEST(MeshIo, StlReadsAsciiAndBinaryAndWeldsCorners) {
  expect_unit_tetra(read_stl(test_file("tetra_ascii.stl")));
  const std::string binary = binary_tetra_stl();
  ASSERT_EQ(binary.size(), 84u + 4 * 50);
  expect_unit_tetra(read_stl(binary));
  EXPECT_EQ(read_stl(binary).F, read_stl(test_file("tetra_ascii.stl")).F);
  // -0.0 and 0.0 are the same point.
  std::string signed_zero = test_file("tetra_ascii.stl");
  signed_zero.replace(signed_zero.find("vertex 0 0 0"), 12, "vertex -0 0 0");
  EXPECT_EQ(read_stl(signed_zero).V.rows(), 4);
}

TEST(MeshIo, StlErrorsNameTheLineOrByteOffset) {
  const std::string binary = binary_tetra_stl();
  EXPECT_NE(error_of([&] {
              read_stl(binary.substr(0, 180));
            }).find("STL (binary) byte offset 80: declares 4 triangles, which need 284 bytes, but the file has 180"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_stl(std::string(50, '\0')); }).find("STL (binary) byte offset 50: truncated"),
            std::string::npos);
  const std::string ascii = test_file("tetra_ascii.stl");
  EXPECT_NE(error_of([&] { read_stl(ascii.substr(0, ascii.find("endloop"))); }).find("ends in the middle of a facet"),
            std::string::npos);
  std::string bad = ascii;
  bad.replace(bad.find("vertex 0 1 0"), 12, "vertex 0 1 q");
  EXPECT_NE(error_of([&] { read_stl(bad); }).find("STL line 5: vertex coordinate 'q' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              read_stl("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nendfacet\n");
            }).find("STL line 5: expected 'vertex' or 'endloop', found 'endfacet'"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_stl("solid empty\nendsolid empty\n"); }).find("STL: the file has no faces"),
            std::string::npos);
}

// ----- detection, dispatch, robustness

TEST(MeshIo, FormatFromExtensionThenContent) {
  EXPECT_EQ(detect_mesh_format("a/b/Model.OBJ", ""), MeshFormat::Obj);
  EXPECT_EQ(detect_mesh_format("x.off", ""), MeshFormat::Off);
  EXPECT_EQ(detect_mesh_format("x.Ply", ""), MeshFormat::Ply);
  EXPECT_EQ(detect_mesh_format("x.stl", ""), MeshFormat::Stl);
  EXPECT_EQ(detect_mesh_format("upload", test_file("cube_ascii.ply")), MeshFormat::Ply);
  EXPECT_EQ(detect_mesh_format("upload", test_file("tetra.off")), MeshFormat::Off);
  EXPECT_EQ(detect_mesh_format("upload", binary_tetra_stl()), MeshFormat::Stl);
  EXPECT_EQ(detect_mesh_format("upload", test_file("cube_quads.obj")), MeshFormat::Obj);
  EXPECT_NE(error_of([] { detect_mesh_format("notes.txt", "hello"); }).find("unknown mesh format"), std::string::npos);
  EXPECT_NE(error_of([] { read_mesh("v 0 0 0\n", "empty.obj"); }).find("empty.obj: OBJ: the file has no faces"),
            std::string::npos);
  expect_unit_cube(read_mesh(test_file("cube.off"), "cube.off"));
}

// Parses with every reader; anything but a mesh with faces or an sd::Error fails the test.
void parse_all_safely(const std::string& bytes) {
  for (const auto& [name, reader] : kReaders) {
    try {
      const Mesh m = reader(bytes);
      EXPECT_GT(m.F.rows(), 0) << name;
      EXPECT_TRUE((m.F.array() >= 0).all() && (m.F.array() < m.V.rows()).all()) << name;
    } catch (const Error&) {
    }
  }
}

// Every reader failure is a ParseError, also after read_mesh prefixes the file name.
TEST(MeshIo, FailuresAreParseErrors) {
  const char* bad[][2] = {{"f 1 2 3\n", "a.obj"},
                          {"OFF\n3 1\n", "b.off"},
                          {"ply\nformat ascii 1.0\n", "c.ply"},
                          {"solid x\nfacet\n", "d.stl"},
                          {"??", "e.xyz"}};
  for (const auto& [bytes, name] : bad) {
    try {
      read_mesh(bytes, name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::ParseError) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(std::string(name) == "e.xyz" ? "'e.xyz'" : name, 0), 0u) << e.what();
    }
  }
}

TEST(MeshIo, RandomAndMutatedBytesNeverCrash) {
  std::mt19937 rng(2024);
  const std::vector<std::string> valid = {
      test_file("cube_quads.obj"), test_file("cube.off"),        test_file("cube_ascii.ply"), binary_cube_ply(false),
      binary_cube_ply(true),       test_file("tetra_ascii.stl"), binary_tetra_stl()};
  for (int round = 0; round < 3000; ++round) {
    std::string bytes;
    if (round % 2 == 0) {
      bytes.resize(rng() % 600);
      for (char& c : bytes) c = static_cast<char>(rng());
    } else {
      bytes = valid[rng() % valid.size()];
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits && !bytes.empty(); ++e) {
        const size_t at = rng() % bytes.size();
        switch (rng() % 3) {
          case 0: bytes[at] = static_cast<char>(rng()); break;
          case 1: bytes.resize(at); break;
          default: bytes.insert(at, 1, "0123456789 -.e\n/"[rng() % 16]); break;
        }
      }
    }
    parse_all_safely(bytes);
  }
}

TEST(MeshIo, FuzzRegressionInputsParseOrThrowSdError) {
  const std::filesystem::path folder = std::string(SD_TEST_DATA_DIR) + "/fuzz-regressions";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (!entry.is_regular_file() || entry.path().extension() == ".md") continue;
    SCOPED_TRACE(entry.path().filename().string());
    parse_all_safely(test::read_file(entry.path().string()));
    ++count;
  }
  RecordProperty("regression_inputs", count);
}

// ----- the shared test meshes (skipped when ../shared/data is absent)

TEST(MeshIo, SharedMeshesHaveTheDocumentedSizes) {
  SD_REQUIRE_SHARED_DATA("armadillo.obj");
  const struct {
    const char* name;
    int vertices, faces;
  } table[] = {{"gargoyle.obj", 2674, 5344},    {"armadillo.obj", 3990, 7976},    {"handbones.obj", 5497, 11026},
               {"spikybox.obj", 60802, 121600}, {"wiresphere.obj", 48964, 98304}, {"spot.obj", 2930, 5856},
               {"armadillo_cage.obj", 77, 150}};
  for (const auto& row : table) {
    const Mesh m = test::load_shared_mesh(row.name);
    EXPECT_EQ(m.V.rows(), row.vertices) << row.name;
    EXPECT_EQ(m.F.rows(), row.faces) << row.name;
    // Same mesh after an OBJ write/read round trip.
    const Mesh back = read_obj(write_obj(m));
    EXPECT_TRUE(back.V == m.V && back.F == m.F) << row.name;
  }
}

}  // namespace
}  // namespace sd
