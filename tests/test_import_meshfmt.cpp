// OBJ, PLY, OFF and STL import: tiny meshes drawn in comments (written to a
// temporary folder and read through geom::import_file), the same real mesh in
// four formats, a brute-force topology count on every real file that loads,
// and hostile input (assimp's invalid/ folder, Draco's edge cases, every
// truncation and random byte damage) that must load or be refused cleanly.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "geom/import.h"
#include "geom/report.h"

namespace fs = std::filesystem;
using namespace geom;

namespace {

const std::string kAssimp = "/usr/share/assimp/models";
const std::string kDraco = std::string(GEOM_TEST_DATA) + "/draco";
const std::string kOpenscad = "/usr/share/openscad";  // Debian's openscad-testing-data: broken STL files

fs::path temp_path() { return fs::temp_directory_path() / ("geom_test_meshfmt_" + std::to_string(::getpid())); }

// The test's files live in one folder, removed when the process ends.
struct TempDirCleanup {
  ~TempDirCleanup() {
    std::error_code ec;
    fs::remove_all(temp_path(), ec);
  }
} temp_dir_cleanup;

fs::path temp_dir() {
  static fs::path dir = [] {
    fs::path d = temp_path();
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

std::string write_file(const std::string& name, const std::string& bytes) {
  fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  return p.string();
}

ImportResult load_text(const std::string& name, const std::string& bytes) {
  return import_file(write_file(name, bytes));
}

std::vector<unsigned char> read_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::vector<unsigned char>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// The triangles of a scene as position triples, to compare across formats.
std::vector<std::array<float, 9>> triangles_of(const Scene& s) {
  std::vector<std::array<float, 9>> t(s.triangle_count());
  for (size_t i = 0; i < t.size(); ++i)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) t[i][3 * c + k] = s.positions[3 * s.indices[3 * i + c] + k];
  return t;
}

// The load either worked or failed with "NAME: reason"; nothing else is allowed.
void expect_clean(const ImportResult& r, const std::string& name) {
  if (r.ok) {
    EXPECT_EQ(r.scene.indices.size() % 3, 0u);
    EXPECT_EQ(r.scene.sources.size(), r.scene.triangle_count());
    for (uint32_t i : r.scene.indices) ASSERT_LT(i, r.scene.vertex_count());
    EXPECT_TRUE(r.error.empty());
  } else {
    ASSERT_EQ(r.error.rfind(name + ": ", 0), 0u) << r.error;
    EXPECT_GT(r.error.size(), name.size() + 2) << "no reason given";
    EXPECT_EQ(r.error.find('\n'), std::string::npos) << "one line: " << r.error;
  }
}

// ---------------------------------------------------------------------------
// Brute force: weld by exact position (std::map over xyz, -0 == +0) and count
// edges with a std::map over sorted vertex pairs; independent of geom::weld
// and geom::build_topology.
struct Brute {
  uint64_t triangles = 0, vertices = 0, edges = 0, boundary = 0, manifold = 0, inconsistent = 0, non_manifold = 0,
           collapsed = 0, max_faces = 0;
};

Brute brute_force(const Scene& s) {
  Brute b;
  std::map<std::array<float, 3>, uint32_t> ids;
  std::vector<uint32_t> welded(s.vertex_count());
  for (size_t v = 0; v < s.vertex_count(); ++v) {
    std::array<float, 3> key = {s.positions[3 * v] + 0.0f, s.positions[3 * v + 1] + 0.0f,
                                s.positions[3 * v + 2] + 0.0f};
    welded[v] = ids.emplace(key, uint32_t(ids.size())).first->second;
  }
  std::map<std::pair<uint32_t, uint32_t>, std::pair<int, int>> edges;  // (forward, backward) uses
  std::set<uint32_t> used;
  b.triangles = s.triangle_count();
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    uint32_t v[3] = {welded[s.indices[3 * t]], welded[s.indices[3 * t + 1]], welded[s.indices[3 * t + 2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
      ++b.collapsed;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      used.insert(v[k]);
      uint32_t a = v[k], c = v[(k + 1) % 3];
      auto& e = edges[{std::min(a, c), std::max(a, c)}];
      (a < c ? e.first : e.second)++;
    }
  }
  b.vertices = used.size();
  b.edges = edges.size();
  for (auto& [key, e] : edges) {
    uint64_t n = uint64_t(e.first + e.second);
    b.max_faces = std::max(b.max_faces, n);
    if (n == 1)
      ++b.boundary;
    else if (n == 2)
      (e.first == 1 ? b.manifold : b.inconsistent)++;
    else
      ++b.non_manifold;
  }
  return b;
}

void expect_report_matches_brute_force(const Scene& s, const std::string& what) {
  Report rep;
  analyze(s, {}, rep);
  Brute b = brute_force(s);
  const TopologyStats& t = rep.stats;
  EXPECT_EQ(t.triangles, b.triangles) << what;
  EXPECT_EQ(t.vertices, b.vertices) << what;
  EXPECT_EQ(t.edges, b.edges) << what;
  EXPECT_EQ(t.boundary_edges, b.boundary) << what;
  EXPECT_EQ(t.manifold_edges, b.manifold) << what;
  EXPECT_EQ(t.inconsistent_edges, b.inconsistent) << what;
  EXPECT_EQ(t.non_manifold_edges, b.non_manifold) << what;
  EXPECT_EQ(t.collapsed_triangles, b.collapsed) << what;
  if (b.edges) EXPECT_EQ(uint64_t(t.max_edge_faces), b.max_faces) << what;
  EXPECT_EQ(t.closed, b.boundary == 0 && b.non_manifold == 0) << what;
}

// ---------------------------------------------------------------------------
// OBJ
//
//   4 ------- 3        unit square in z = 0, one quad 1 2 3 4 (counter-
//   |       / |        clockwise seen from +z), fanned from its first
//   |     /   |        corner into (1,2,3) and (1,3,4)
//   |   /     |
//   | /       |
//   1 ------- 2
const char* kSquareV = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

TEST(ImportObj, QuadIsFannedFromItsFirstCorner) {
  ImportResult r = load_text("square.obj", std::string(kSquareV) + "f 1 2 3 4\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.scene.vertex_count(), 4u);
  EXPECT_EQ(r.scene.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_TRUE(r.scene.warnings.empty());
}

TEST(ImportObj, CornerFormsAndNegativeIndicesGiveTheSameFaces) {
  const std::string vt = "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n";
  const char* faces[] = {"f 1 2 3 4\n",
                         "f 1/1 2/2 3/3 4/4\n",
                         "f 1//1 2//1 3//1 4//1\n",
                         "f 1/1/1 2/2/1 3/3/1 4/4/1\n",
                         "f -4 -3 -2 -1\n",
                         "f -4/-4/-1 -3/-3/-1 -2//-1 -1\n",
                         "f\t1   2\t3 4   \n",
                         "f 1 2 3 4 # a quad\n",
                         "f 1 2 3 4#\n"};
  for (const char* f : faces) {
    ImportResult r = load_text("forms.obj", kSquareV + vt + f);
    ASSERT_TRUE(r.ok) << f << r.error;
    EXPECT_EQ(r.scene.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3})) << f;
  }
  // A negative index counts back from the latest vertex at that point of the file.
  ImportResult r = load_text("relative.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf -4 -2 -1\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.scene.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

// Two triangles in two groups, and one before any group:
//   f 1 2 3  (group 0, before any o/g)   o a / f 1 3 4 (group 1)
//   g b      (no face: gets no number)   g c / f 2 3 4, f 1 2 4 (group 2)
TEST(ImportObj, ObjectsAndGroupsNumberTheMeshes) {
  ImportResult r =
      load_text("groups.obj", std::string(kSquareV) + "f 1 2 3\no a\nf 1 3 4\ng b\ng c\nf 2 3 4\nf 1 2 4\n");
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.scene.sources.size(), 4u);
  EXPECT_EQ(r.scene.sources[0].mesh, 0u);
  EXPECT_EQ(r.scene.sources[1].mesh, 1u);
  EXPECT_EQ(r.scene.sources[2].mesh, 2u);
  EXPECT_EQ(r.scene.sources[3].mesh, 2u);
  for (const TriangleSource& s : r.scene.sources) EXPECT_EQ(s.file, 0u);
}

TEST(ImportObj, LinesAndPointsAreSkippedWithOneWarning) {
  const std::string path = write_file("lines.obj", std::string(kSquareV) + "l 1 2\nl 2 3 4\np 1\nf 1 2 3\n");
  ImportResult r = import_file(path);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.scene.triangle_count(), 1u);
  ASSERT_EQ(r.scene.warnings.size(), 1u);
  EXPECT_EQ(r.scene.warnings[0].rfind(path + ": 3 line and point", 0), 0u) << r.scene.warnings[0];
}

TEST(ImportObj, LineEndingsContinuationAndMissingFinalNewline) {
  const std::string lf = std::string(kSquareV) + "f 1 2 3 4\n";
  auto with_eol = [&](const std::string& eol) {
    std::string s;
    for (char c : lf) s += c == '\n' ? eol : std::string(1, c);
    return s;
  };
  for (const std::string& text :
       {with_eol("\r\n"), with_eol("\r"), lf.substr(0, lf.size() - 1), std::string(kSquareV) + "f 1 2 \\\n 3 4\n",
        std::string(kSquareV) + "f 1 2 \\\r\n3 \\  \r\n 4", "\xEF\xBB\xBF" + lf}) {
    ImportResult r = load_text("eol.obj", text);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.scene.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  }
  // Continued lines keep the physical line numbers right: the bad face is on line 7.
  ImportResult r = load_text("contline.obj", "v 0 0 0\nv 1 \\\n 0 0\nv 1 \\\n1 0\n\nf 1 2 9\n");
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find(": line 7: face index 9 out of range (3 vertices)"), std::string::npos) << r.error;
}

TEST(ImportObj, OutOfRangeIndexNamesTheLine) {
  // Line 12 uses vertex 40 of 8.
  std::string text = "# cube corners\n";
  for (int i = 0; i < 8; ++i)
    text += "v " + std::to_string(i & 1) + " " + std::to_string(i >> 1 & 1) + " " + std::to_string(i >> 2 & 1) + "\n";
  text += "f 1 2 3\nf 1 3 4\nf 1 40 2\n";
  const std::string path = write_file("range.obj", text);
  ImportResult r = import_file(path);
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.error, path + ": line 12: face index 40 out of range (8 vertices)");
  for (const char* bad : {"f 1 2 0\n", "f 1 2 -9\n", "f 1 2 x\n", "f 1 2 3/x\n", "f 1 2 /3\n", "f 1 2 3/1/1/1\n",
                          "v 1 2\n", "v 1 2 3.1+e2\n"}) {
    ImportResult b = load_text("bad.obj", std::string(kSquareV) + bad);
    EXPECT_FALSE(b.ok) << bad;
    EXPECT_NE(b.error.find("line 5: "), std::string::npos) << b.error;
  }
}

// Every refusal carries its kind as well as its message (geom/status.h): a
// format's own rules broken, a count over the caller's limit, an unused or
// used non-finite vertex, a file that cannot be read, an unknown type.
TEST(ImportErrors, EachRefusalCarriesItsCode) {
  ImportResult r = load_text("range.obj", std::string(kSquareV) + "f 1 2 9\n");
  EXPECT_EQ(r.code, ErrorCode::Malformed) << r.error;
  r = load_text("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  EXPECT_EQ(r.code, ErrorCode::NonFinite) << r.error;
  EXPECT_NE(r.error.find("nan.obj: triangle 0 uses vertex 2 with a non-finite coordinate"), std::string::npos)
      << r.error;
  r = load_text("unused_nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 1 0\nf 1 2 3\n");
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.code, ErrorCode::None);
  ImportOptions limit;
  limit.max_triangles = 1;
  const std::string text = std::string(kSquareV) + "f 1 2 3\nf 1 3 4\n";
  r = import_memory("two.obj", text.data(), text.size(), limit);
  EXPECT_EQ(r.code, ErrorCode::TooLarge) << r.error;
  EXPECT_EQ(r.error, "two.obj: 2 triangles, over the limit of 1");
  r = import_file((temp_path() / "missing.obj").string());
  EXPECT_EQ(r.code, ErrorCode::Io) << r.error;
  r = load_text("mesh.xyz", "v 0 0 0\n");
  EXPECT_EQ(r.code, ErrorCode::Malformed) << r.error;
  EXPECT_FALSE(r.ok);
}

TEST(ImportObj, Utf16IsRefusedClearly) {
  for (bool big : {false, true}) {
    std::string text = std::string(kSquareV) + "f 1 2 3\n", u16 = big ? "\xFE\xFF" : "\xFF\xFE";
    for (char c : text) u16 += big ? std::string{'\0', c} : std::string{c, '\0'};
    const std::string path = write_file("utf16.obj", u16);
    ImportResult r = import_file(path);
    ASSERT_FALSE(r.ok);
    EXPECT_EQ(r.error.rfind(path + ": UTF-16", 0), 0u) << r.error;
  }
  ImportResult r = import_file(kAssimp + "/OBJ/box_UTF16BE.obj");
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("UTF-16"), std::string::npos) << r.error;
}

TEST(ImportObj, EmptyAndCommentOnlyFilesGiveAnEmptyScene) {
  for (const char* text : {"", "# nothing\n", "\n\n\r\n", "vt 0 0\nvn 0 0 1\nusemtl x\ns off\n"}) {
    ImportResult r = load_text("empty.obj", text);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.scene.triangle_count(), 0u);
  }
}

// ---------------------------------------------------------------------------
// PLY
//
//          3               tetrahedron, outward winding:
//         /|\              0 = (0,0,0), 1 = (1,0,0), 2 = (0,1,0), 3 = (0,0,1)
//        / | \             faces (0,2,1) (0,1,3) (1,2,3) (0,3,2)
//       0--+--1
//        \ | /
//          2
const float kTet[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const uint32_t kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};

// Appends `v` as a scalar of `type` in the given byte order.
void put(std::string& out, const std::string& type, double v, bool big) {
  unsigned char b[8];
  size_t n = 0;
  auto store = [&](auto x) {
    n = sizeof x;
    std::memcpy(b, &x, n);
  };
  if (type == "char")
    store(int8_t(v));
  else if (type == "uchar")
    store(uint8_t(v));
  else if (type == "short")
    store(int16_t(v));
  else if (type == "ushort")
    store(uint16_t(v));
  else if (type == "int")
    store(int32_t(v));
  else if (type == "uint")
    store(uint32_t(v));
  else if (type == "float")
    store(float(v));
  else
    store(double(v));
  if (big) std::reverse(b, b + n);
  out.append(reinterpret_cast<const char*>(b), n);
}

// The tetrahedron as a PLY in `format`, coordinates of `xyz_type`, list count
// and index types as given, with an extra vertex property and an extra element.
std::string tet_ply(const std::string& format, const std::string& xyz_type, const std::string& count_type,
                    const std::string& index_type) {
  std::string h = "ply\nformat " + format + " 1.0\ncomment made by the test\n";
  h += "element vertex 4\nproperty " + xyz_type + " x\nproperty uchar red\nproperty " + xyz_type + " y\nproperty " +
       xyz_type + " z\n";
  h += "element edge 1\nproperty int vertex1\nproperty list uchar int other\n";
  h += "element face 4\nproperty list " + count_type + " " + index_type + " vertex_indices\nproperty float q\n";
  h += "end_header\n";
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  auto val = [&](const std::string& type, double v) {
    if (ascii)
      h += std::to_string(v) + " ";
    else
      put(h, type, v, big);
  };
  for (auto& p : kTet) {
    val(xyz_type, p[0]), val("uchar", 200), val(xyz_type, p[1]), val(xyz_type, p[2]);
    if (ascii) h += "\n";
  }
  val("int", 7), val("uchar", 2), val("int", 1), val("int", 2);
  if (ascii) h += "\n";
  for (auto& f : kTetFaces) {
    val(count_type, 3);
    for (uint32_t i : f) val(index_type, i);
    val("float", 0.5);
    if (ascii) h += "\n";
  }
  return h;
}

void expect_tetrahedron(const Scene& s) {
  ASSERT_EQ(s.vertex_count(), 4u);
  for (int v = 0; v < 4; ++v)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s.positions[3 * v + k], kTet[v][k]);
  ASSERT_EQ(s.triangle_count(), 4u);
  for (int f = 0; f < 4; ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s.indices[3 * f + k], kTetFaces[f][k]);
}

TEST(ImportPly, EveryFormatAndScalarTypeGivesTheSameTetrahedron) {
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"})
    for (const char* xyz : {"float", "double", "char", "uchar", "short", "int", "uint", "ushort"})
      for (const char* count : {"uchar", "ushort", "int", "uint"})
        for (const char* index : {"int", "uint", "ushort", "char", "uchar", "short"}) {
          ImportResult r = load_text("tet.ply", tet_ply(format, xyz, count, index));
          ASSERT_TRUE(r.ok) << format << " " << xyz << " " << count << " " << index << ": " << r.error;
          expect_tetrahedron(r.scene);
        }
}

TEST(ImportPly, AliasesVertexIndexAndCrOnlyHeader) {
  std::string text =
      "ply\rformat ascii 1.0\relement vertex 4\rproperty float32 x\rproperty float32 y\r"
      "property float32 z\relement face 1\rproperty list uint8 int32 vertex_index\rend_header\r"
      "0 0 0\r1 0 0\r1 1 0\r0 1 0\r4 0 1 2 3\r";
  ImportResult r = load_text("cr.ply", text);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.scene.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));  // quad fanned
}

//   0 --- 2 --- 4        one strip 0 1 2 3 4 5, then -1, then 2 3 4:
//   | \   | \   |        triangles (0,1,2) (2,1,3) (2,3,4) (4,3,5) (2,3,4)
//   1 --- 3 --- 5        (winding alternates; the restart starts over)
TEST(ImportPly, TriangleStripsWithRestart) {
  std::string text =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
      "0 1 0\n0 0 0\n1 1 0\n1 0 0\n2 1 0\n2 0 0\n10 0 1 2 3 4 5 -1 2 3 4\n";
  ImportResult r = load_text("strips.ply", text);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.scene.indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5, 2, 3, 4}));
}

TEST(ImportPly, HostileHeadersAreRefusedBeforeAllocating) {
  const std::string head = "ply\nformat binary_little_endian 1.0\n";
  struct Case {
    std::string text, expect;
  } cases[] = {
      {head + "element vertex 3000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
       "claims 3000000000 entries"},
      {head + "element vertex 18446744073709551615\nproperty float x\nend_header\n",
       "element needs a name and a count"},
      {head +
           "element vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
           "property list uint int vertex_indices\nend_header\n" +
           std::string("\0\0\0\0\0\0\0\0\0\0\0\0\xff\xff\xff\x7f", 16),
       "claims 2147483647 items"},
      {head +
           "element vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
           "property list uchar int vertex_indices\nend_header\n" +
           std::string("\0\0\0\0\0\0\0\0\0\0\0\0\x03\0\0\0\0\x28\0\0\0\0\0\0\0", 25),
       "face 0: vertex index 40 out of range (1 vertices)"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement "
       "face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n3 0 0 -1\n",
       "face 0: vertex index -1 out of range"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
       "no x, y and z"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no end_header"},
      {"ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown format"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "property before any element"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n", "unknown property type"},
      {"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
       "end_header\n0.0000 0.0000 0.0000\n1 1\n",
       "vertex 1: file ends early for property 'z'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n300 0 0 0\n",
       "face 0: bad value for the length"},
      {"solid\n", "not a PLY file"},
  };
  for (const Case& c : cases) {
    const std::string path = write_file("hostile.ply", c.text);
    ImportResult r = import_file(path);
    ASSERT_FALSE(r.ok) << c.expect;
    EXPECT_EQ(r.error.rfind(path + ": ", 0), 0u) << r.error;
    EXPECT_NE(r.error.find(c.expect), std::string::npos) << r.error;
  }
}

TEST(ImportPly, PointCloudLoadsWithAWarning) {
  ImportResult r = import_file(kDraco + "/point_cloud_test_pos.ply");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.scene.triangle_count(), 0u);
  EXPECT_GT(r.scene.vertex_count(), 0u);
  ASSERT_FALSE(r.scene.warnings.empty());
  EXPECT_NE(r.scene.warnings[0].find("point cloud"), std::string::npos);
}

// ---------------------------------------------------------------------------
// OFF
//
//     7-------6         unit cube, 8 corners (bit 0 = x, bit 1 = y, bit 2 = z),
//    /|      /|         six quads wound outwards; each fans into 2 triangles:
//   4-------5 |         12 triangles, closed, 18 edges, Euler characteristic 2
//   | 3-----|-2
//   |/      |/
//   0-------1
const char* kCubeCorners = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n";
const char* kCubeQuads = "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";

void expect_closed_cube(const ImportResult& r) {
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.scene.triangle_count(), 12u);
  Report rep;
  analyze(r.scene, {}, rep);
  EXPECT_TRUE(rep.stats.closed);
  EXPECT_EQ(rep.stats.edges, 18u);
  EXPECT_EQ(rep.stats.manifold_edges, 18u);
  EXPECT_EQ(rep.stats.euler_characteristic, 2);
}

TEST(ImportOff, CubeInEveryVariant) {
  expect_closed_cube(load_text("cube.off", std::string("OFF\n8 6 12\n") + kCubeCorners + kCubeQuads));
  expect_closed_cube(load_text("cube.off", std::string("OFF 8 6 0 ") + kCubeCorners + kCubeQuads));
  expect_closed_cube(load_text("cube.off", std::string("8 6 0\n") + kCubeCorners + kCubeQuads));  // no keyword
  // Comments, blank lines, CRLF, per-face colours.
  std::string commented = "# a cube\r\nOFF # keyword\r\n\r\n# counts\r\n8 6 0\r\n";
  std::string corners, quads;
  for (char c : std::string(kCubeCorners)) corners += c == '\n' ? std::string(" # c\r\n\r\n") : std::string(1, c);
  for (char c : std::string(kCubeQuads)) quads += c == '\n' ? std::string(" 255 0 0 1\r\n") : std::string(1, c);
  expect_closed_cube(load_text("cube.off", commented + corners + quads));
  // COFF with RGBA vertex colours, NOFF with normals, CNOFF, STOFF, 4OFF with w = 2.
  auto variant = [&](const std::string& kw, const std::string& extra, bool four) {
    std::string s = kw + "\n8 6 0\n";
    for (int v = 0; v < 8; ++v) {
      double scale = four ? 2 : 1;
      s += std::to_string((v == 1 || v == 2 || v == 5 || v == 6) * scale) + " " +
           std::to_string((v == 2 || v == 3 || v == 6 || v == 7) * scale) + " " + std::to_string((v >= 4) * scale) +
           (four ? " 2" : "") + " " + extra + "\n";
    }
    return s + kCubeQuads;
  };
  expect_closed_cube(load_text("c.off", variant("COFF", "0.5 0.5 0.5 1", false)));
  expect_closed_cube(load_text("n.off", variant("NOFF", "0 0 1", false)));
  expect_closed_cube(load_text("cn.off", variant("CNOFF", "0 0 1 255 0 0", false)));
  expect_closed_cube(load_text("st.off", variant("STOFF", "0.25 0.75", false)));
  expect_closed_cube(load_text("4.off", variant("4OFF", "", true)));
  expect_closed_cube(load_text("nd.off", "nOFF 3\n" + variant("", "", false).substr(1)));
}

TEST(ImportOff, HostileCountsAndIndicesAreRefused) {
  struct Case {
    std::string text, expect;
  } cases[] = {
      {"OFF\n353535235358 6 0\n0 0 0\n", "header claims 353535235358 vertices"},
      {"OFF\n3 99999999999 0\n0 0 0\n1 0 0\n0 1 0\n", "99999999999 faces"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "line 6: face 0: vertex index 3 out of range (3 vertices)"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n", "bad vertex index '-1'"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "expected 3 vertex indices"},
      {"OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "line 4: vertex 1 needs 3 coordinates"},
      {"OFF\n3 1 0\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n", "bad number 'x'"},
      {"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "file ends before face 1 of 2"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n", "claims 4000000000 vertices"},
      {"OFF BINARY\n3 1 0\n", "binary OFF is not supported"},
      {"XOFF\n", "unknown OFF keyword"},
      {"ply\n", "not an OFF file"},
      {"OFF\n", "expected the vertex and face counts"},
      {"", "empty file"},
  };
  for (const Case& c : cases) {
    const std::string path = write_file("hostile.off", c.text);
    ImportResult r = import_file(path);
    ASSERT_FALSE(r.ok) << c.expect;
    EXPECT_EQ(r.error.rfind(path + ": ", 0), 0u) << r.error;
    EXPECT_NE(r.error.find(c.expect), std::string::npos) << r.error;
  }
  ImportResult r = import_file(kAssimp + "/invalid/OutOfMemory.off");
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("353535235358"), std::string::npos) << r.error;
}

// ---------------------------------------------------------------------------
// STL
//
//   2                   one triangle (0,0,0) (1,0,0) (0,1,0), normal +z,
//   | \                 written binary with a header that starts "solid"
//   0---1               and as ASCII; STL shares no vertices
std::string binary_stl(const std::string& header80, const std::vector<std::array<float, 9>>& tris) {
  std::string s = header80;
  s.resize(80, ' ');
  uint32_t n = uint32_t(tris.size());
  put(s, "uint", n, false);
  for (auto& t : tris) {
    for (int k = 0; k < 3; ++k) put(s, "float", k == 2 ? 1 : 0, false);
    for (float f : t) put(s, "float", f, false);
    s += std::string(2, '\0');
  }
  return s;
}

TEST(ImportStl, BinaryThatBeginsWithSolidAndAscii) {
  const std::array<float, 9> tri = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  ImportResult b = load_text("bin.stl", binary_stl("solid but binary", {tri, tri}));
  ASSERT_TRUE(b.ok) << b.error;
  ASSERT_EQ(b.scene.triangle_count(), 2u);
  EXPECT_EQ(b.scene.vertex_count(), 6u);  // no sharing
  EXPECT_EQ(triangles_of(b.scene)[1], tri);
  for (const TriangleSource& s : b.scene.sources) EXPECT_EQ(s.mesh, TriangleSource::kNone);

  ImportResult a = load_text("ascii.stl",
                             "solid my part\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
                             "   vertex 0 1 0\n  endloop\n endfacet\nendsolid my part\n"
                             "SOLID second\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\nVERTEX 1 1 0\n"
                             "VERTEX 0 1 0\nENDLOOP\nENDFACET\nENDSOLID");
  ASSERT_TRUE(a.ok) << a.error;
  ASSERT_EQ(a.scene.triangle_count(), 3u);  // the quad facet is fanned
  EXPECT_EQ(a.scene.vertex_count(), 7u);
  EXPECT_EQ(triangles_of(a.scene)[0], tri);
  EXPECT_EQ(triangles_of(a.scene)[2], (std::array<float, 9>{0, 0, 0, 1, 1, 0, 0, 1, 0}));
}

TEST(ImportStl, BadFilesAreRefused) {
  const std::array<float, 9> tri = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string two = binary_stl("binary", {tri, tri});
  struct Case {
    std::string text, expect;
  } cases[] = {
      {two.substr(0, two.size() - 1), "header says 2 triangles (184 bytes) but the file has 183"},
      {binary_stl("x", {}).substr(0, 83), "too short for a binary STL"},
      {"", "empty file"},
      {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n", "bad vertex coordinate"},
      {"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "file ends inside a facet"},
      {"solid x\nvertex 0 0 0\n", "line 2: vertex outside a facet"},
      {"solid x\nfacet\nfacet\n", "facet without endfacet"},
      {"solid x\nbanana\n", "unexpected 'banana'"},
  };
  for (const Case& c : cases) {
    const std::string path = write_file("bad.stl", c.text);
    ImportResult r = import_file(path);
    ASSERT_FALSE(r.ok) << c.expect;
    EXPECT_EQ(r.error.rfind(path + ": ", 0), 0u) << r.error;
    EXPECT_NE(r.error.find(c.expect), std::string::npos) << r.error;
  }
  // Trailing bytes after complete records only warn, also when the header begins with "solid".
  for (const char* header : {"x", "solid x"}) {
    ImportResult r = load_text("trail.stl", binary_stl(header, {tri}) + "junk");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.scene.triangle_count(), 1u);
    ASSERT_EQ(r.scene.warnings.size(), 1u);
    EXPECT_NE(r.scene.warnings[0].find("4 bytes after the last binary STL triangle"), std::string::npos);
  }
}

// ---------------------------------------------------------------------------
// Random round trips: random polygon meshes (coordinates tiny, huge, far from
// the origin, signed zeros, subnormals; corners repeated at random) written in
// every format with random formatting choices; each import must give back
// exactly the fan triangles of every polygon, bit for bit.

std::string num(float f) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", double(f));
  return buf;
}

struct RandomMesh {
  std::vector<float> pos;
  std::vector<std::vector<uint32_t>> polys;
  std::vector<std::array<float, 9>> fan() const {
    std::vector<std::array<float, 9>> t;
    for (auto& p : polys)
      for (size_t i = 1; i + 1 < p.size(); ++i) {
        std::array<float, 9> a;
        uint32_t c[3] = {p[0], p[i], p[i + 1]};
        for (int k = 0; k < 3; ++k)
          for (int j = 0; j < 3; ++j) a[3 * k + j] = pos[3 * c[k] + j];
        t.push_back(a);
      }
    return t;
  }
};

RandomMesh random_mesh(std::mt19937& rng) {
  RandomMesh m;
  const size_t nv = 1 + rng() % 40;
  std::uniform_real_distribution<float> u(-1, 1);
  const float scales[] = {1, 1e-30f, 1e6f, 3e38f, 1e-40f};
  const float offsets[] = {0, 1e7f, -123456.78f};
  for (size_t i = 0; i < 3 * nv; ++i) {
    float v = u(rng) * scales[rng() % 5] + offsets[rng() % 3];
    if (rng() % 20 == 0) v = -0.0f;
    m.pos.push_back(v);
  }
  const size_t nf = rng() % 25;
  for (size_t f = 0; f < nf; ++f) {
    std::vector<uint32_t> p(3 + rng() % 6);
    for (uint32_t& i : p) i = uint32_t(rng() % nv);
    m.polys.push_back(p);
  }
  return m;
}

std::string random_eol(std::mt19937& rng) {
  const char* e[] = {"\n", "\r\n", "\r"};
  return e[rng() % 3];
}

std::string write_obj(const RandomMesh& m, std::mt19937& rng) {
  const std::string eol = random_eol(rng);
  std::string s = rng() % 2 ? "# random" + eol : "";
  const size_t nv = m.pos.size() / 3;
  for (size_t v = 0; v < nv; ++v) {
    s += "v " + num(m.pos[3 * v]) + (rng() % 4 ? " " : "\t  ") + num(m.pos[3 * v + 1]) + " " + num(m.pos[3 * v + 2]);
    s += (rng() % 5 ? "" : " 1") + eol;
    if (rng() % 3 == 0) s += "vt 0.5 0.5" + eol + "vn 0 0 1" + eol;
  }
  for (auto& p : m.polys) {
    if (rng() % 5 == 0) s += (rng() % 2 ? "g part" : "o thing") + eol;
    s += "f";
    for (size_t i = 0; i < p.size(); ++i) {
      std::string idx = rng() % 3 ? std::to_string(p[i] + 1) : std::to_string(int64_t(p[i]) - int64_t(nv));
      switch (rng() % 4) {
        case 0:
          s += " " + idx;
          break;
        case 1:
          s += " " + idx + "/1";
          break;
        case 2:
          s += " " + idx + "//1";
          break;
        default:
          s += " " + idx + "/1/1";
          break;
      }
      if (rng() % 10 == 0 && i + 1 < p.size()) s += " \\" + eol;
    }
    s += eol;
  }
  if (rng() % 2 && !s.empty()) s.resize(s.size() - eol.size());  // no final line end
  return s;
}

std::string write_off(const RandomMesh& m, std::mt19937& rng) {
  const std::string eol = random_eol(rng);
  std::string s = std::string(rng() % 2 ? "OFF" : "COFF") + eol;
  const bool colour = s[0] == 'C';
  s += (rng() % 2 ? "# counts" + eol : "") + std::to_string(m.pos.size() / 3) + " " + std::to_string(m.polys.size()) +
       " 0" + eol;
  for (size_t v = 0; v < m.pos.size() / 3; ++v)
    s += num(m.pos[3 * v]) + " " + num(m.pos[3 * v + 1]) + " " + num(m.pos[3 * v + 2]) +
         (colour ? " 0.1 0.2 0.3 1" : "") + (rng() % 4 ? "" : " # c") + eol;
  for (auto& p : m.polys) {
    s += std::to_string(p.size());
    for (uint32_t i : p) s += " " + std::to_string(i);
    s += (rng() % 3 ? "" : " 255 0 0") + eol;
  }
  return s;
}

std::string write_ply(const RandomMesh& m, std::mt19937& rng) {
  const char* formats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
  const std::string format = formats[rng() % 3];
  const std::string xyz = rng() % 2 ? "float" : "double";
  const std::string count = rng() % 2 ? "uchar" : "int", index = rng() % 2 ? "int" : "uint";
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  std::string s = "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(m.pos.size() / 3) + "\nproperty " +
                  xyz + " x\nproperty " + xyz + " y\nproperty " + xyz + " z\nproperty uchar red\n" + "element face " +
                  std::to_string(m.polys.size()) + "\nproperty list " + count + " " + index +
                  " vertex_indices\nend_header\n";
  for (size_t v = 0; v < m.pos.size() / 3; ++v) {
    for (int k = 0; k < 3; ++k)
      if (ascii)
        s += num(m.pos[3 * v + k]) + " ";
      else
        put(s, xyz, m.pos[3 * v + k], big);
    if (ascii)
      s += "7\n";
    else
      put(s, "uchar", 7, big);
  }
  for (auto& p : m.polys) {
    if (ascii)
      s += std::to_string(p.size());
    else
      put(s, count, double(p.size()), big);
    for (uint32_t i : p)
      if (ascii)
        s += " " + std::to_string(i);
      else
        put(s, index, i, big);
    if (ascii) s += "\n";
  }
  return s;
}

std::string write_stl(const RandomMesh& m, std::mt19937& rng) {
  auto tris = m.fan();
  if (rng() % 2) return binary_stl(rng() % 2 ? "solid random" : "random", tris);
  const std::string eol = random_eol(rng);
  std::string s = "solid random" + eol;
  for (auto& t : tris) {
    s += "facet normal 0 0 0" + eol + "outer loop" + eol;
    for (int k = 0; k < 3; ++k)
      s += "vertex " + num(t[3 * k]) + " " + num(t[3 * k + 1]) + " " + num(t[3 * k + 2]) + eol;
    s += "endloop" + eol + "endfacet" + eol;
  }
  return s + "endsolid random" + eol;
}

TEST(RoundTrip, RandomPolygonMeshesInEveryFormatGiveTheirFanTriangles) {
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 300; ++trial) {
    RandomMesh m = random_mesh(rng);
    const auto expected = m.fan();
    const std::pair<const char*, std::string> files[] = {{"r.obj", write_obj(m, rng)},
                                                         {"r.off", write_off(m, rng)},
                                                         {"r.ply", write_ply(m, rng)},
                                                         {"r.stl", write_stl(m, rng)}};
    for (auto& [name, text] : files) {
      ImportResult r = import_memory(name, text.data(), text.size());
      ASSERT_TRUE(r.ok) << name << " trial " << trial << ": " << r.error << "\n" << text.substr(0, 2000);
      auto got = triangles_of(r.scene);
      ASSERT_EQ(got.size(), expected.size()) << name << " trial " << trial;
      for (size_t t = 0; t < got.size(); ++t)
        for (int k = 0; k < 9; ++k)
          ASSERT_EQ(std::memcmp(&got[t][k], &expected[t][k], 4), 0)
              << name << " trial " << trial << " triangle " << t << ": " << got[t][k] << " vs " << expected[t][k];
    }
  }
}

// ---------------------------------------------------------------------------
// Real files.

const char* kWuson[] = {"OBJ/WusonOBJ.obj", "OFF/Wuson.off", "PLY/Wuson.ply", "STL/Wuson.stl"};

TEST(RealFiles, WusonInFourFormatsHasTheSameTrianglesAndTopology) {
  std::vector<Report> reports;
  for (const char* rel : kWuson) {
    ImportResult r = import_file(kAssimp + "/" + rel);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.scene.triangle_count(), 3732u) << rel;
    Report rep;
    analyze(r.scene, {}, rep);
    reports.push_back(rep);
  }
  for (size_t i = 1; i < reports.size(); ++i) {
    const TopologyStats &a = reports[0].stats, &b = reports[i].stats;
    EXPECT_EQ(a.vertices, b.vertices) << kWuson[i];
    EXPECT_EQ(a.edges, b.edges) << kWuson[i];
    EXPECT_EQ(a.boundary_edges, b.boundary_edges) << kWuson[i];
    EXPECT_EQ(a.manifold_edges, b.manifold_edges) << kWuson[i];
    EXPECT_EQ(a.inconsistent_edges, b.inconsistent_edges) << kWuson[i];
    EXPECT_EQ(a.non_manifold_edges, b.non_manifold_edges) << kWuson[i];
    EXPECT_EQ(a.collapsed_triangles, b.collapsed_triangles) << kWuson[i];
    EXPECT_EQ(a.components, b.components) << kWuson[i];
    EXPECT_EQ(a.euler_characteristic, b.euler_characteristic) << kWuson[i];
    EXPECT_EQ(a.closed, b.closed) << kWuson[i];
  }
}

bool is_mesh_format(const fs::path& p) {
  std::string e = p.extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e == ".obj" || e == ".ply" || e == ".off" || e == ".stl";
}

std::vector<std::string> real_mesh_files() {
  std::vector<std::string> files;
  for (const std::string& root : {kAssimp, kDraco, kOpenscad}) {
    EXPECT_TRUE(fs::exists(root)) << root << " is missing (tests/data, or scripts/setup.sh's packages)";
    if (!fs::exists(root)) continue;
    for (auto& e : fs::recursive_directory_iterator(root))
      if (e.is_regular_file() && is_mesh_format(e.path())) files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(RealFiles, ReportCountsEqualABruteForceCountOnEveryFileThatLoads) {
  std::vector<std::string> files = real_mesh_files();
  ASSERT_GT(files.size(), 60u) << "assimp-testmodels or the vendored Draco data is missing";
  size_t loaded = 0, triangles = 0;
  for (const std::string& f : files) {
    ImportResult r = import_file(f);
    expect_clean(r, f);
    if (!r.ok) continue;
    ++loaded;
    triangles += r.scene.triangle_count();
    expect_report_matches_brute_force(r.scene, f);
  }
  EXPECT_GT(loaded, 50u);
  EXPECT_GT(triangles, 20000u);
}

TEST(RealFiles, InvalidAndEdgeCaseFilesLoadOrAreRefusedQuickly) {
  std::vector<std::string> files;
  for (auto& e : fs::directory_iterator(kAssimp + "/invalid")) files.push_back(e.path().string());
  for (const char* name :
       {"inf_nan.obj", "deg_faces.obj", "degenerate_mesh.obj", "non_manifold_wrap.obj", "delim_test.ply",
        "float_inf_point_cloud.ply", "int_point_cloud.ply", "point_cloud_test_pos.obj", "point_cloud_test_pos.ply",
        "test_lines.obj", "extra_vertex.obj", "eof_test.obj", "empty_name.obj", "test_extra_whitespace.ply",
        "test_more_datatypes.ply", "test_wrong_attribute_mapping.obj", "triangle_with_degenerate_tex_coords.obj",
        "cube_att_partial.obj"})
    files.push_back(kDraco + "/" + name);
  for (const char* rel : {"OBJ/box_UTF16BE.obj", "OBJ/number_formats.obj", "OBJ/testline.obj", "OBJ/testpoints.obj",
                          "OBJ/point_cloud.obj", "PLY/points.ply", "STL/triangle_with_empty_solid.stl"})
    files.push_back(kAssimp + "/" + rel);
  if (fs::exists(kOpenscad + "/testdata/stl"))
    for (auto& e : fs::directory_iterator(kOpenscad + "/testdata/stl")) files.push_back(e.path().string());
  for (const std::string& f : files) {
    auto t0 = std::chrono::steady_clock::now();
    ImportResult r = import_file(f);
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    expect_clean(r, f);
    EXPECT_LT(s, 1.0) << f;
  }
  // What some of them must give.
  ImportResult nan = import_file(kDraco + "/inf_nan.obj");
  EXPECT_FALSE(nan.ok);
  EXPECT_NE(nan.error.find("non-finite"), std::string::npos) << nan.error;
  ImportResult bad = import_file(kAssimp + "/invalid/malformed.obj");
  EXPECT_EQ(bad.error, kAssimp + "/invalid/malformed.obj: line 23: face index 12 out of range (8 vertices)");
  ImportResult lines = import_file(kDraco + "/test_lines.obj");
  ASSERT_TRUE(lines.ok) << lines.error;
  ASSERT_FALSE(lines.scene.warnings.empty());
  EXPECT_NE(lines.scene.warnings[0].find("line and point statements"), std::string::npos);
  ImportResult wrap = import_file(kDraco + "/non_manifold_wrap.obj");
  ASSERT_TRUE(wrap.ok) << wrap.error;
  Report rep;
  analyze(wrap.scene, {}, rep);
  EXPECT_GE(rep.stats.max_edge_faces, 4u);
  if (fs::exists(kOpenscad + "/testdata/stl")) {
    ImportResult blah = import_file(kOpenscad + "/testdata/stl/invalidvertex.stl");
    EXPECT_EQ(blah.error, kOpenscad + "/testdata/stl/invalidvertex.stl: line 89: bad vertex coordinate 'blah'");
    ImportResult four = import_file(kOpenscad + "/testdata/stl/toomanyvertices.stl");  // one facet of 4 corners
    ASSERT_TRUE(four.ok) << four.error;
    EXPECT_EQ(four.scene.triangle_count(), 14u);
  }
  ImportResult delim = import_file(kDraco + "/delim_test.ply");
  ASSERT_TRUE(delim.ok) << delim.error;
  EXPECT_GT(delim.scene.triangle_count(), 0u);
}

// Every prefix of small files (a few hundred spread over bigger ones) loads or
// is refused cleanly; so does random byte damage.
TEST(RealFiles, TruncationsAndDamageLoadOrAreRefusedCleanly) {
  const std::string files[] = {kAssimp + "/OBJ/box.obj",
                               kDraco + "/cube_att.obj",
                               kDraco + "/octagon.obj",
                               kAssimp + "/PLY/cube.ply",
                               kAssimp + "/PLY/cube_binary.ply",
                               kDraco + "/delim_test.ply",
                               kDraco + "/test_more_datatypes.ply",
                               kAssimp + "/OFF/Cube.off",
                               kAssimp + "/STL/triangle.stl",
                               kAssimp + "/STL/Spider_binary.stl",
                               kAssimp + "/OBJ/WusonOBJ.obj",
                               kAssimp + "/PLY/Wuson.ply",
                               kAssimp + "/OFF/Wuson.off",
                               kAssimp + "/STL/Wuson.stl"};
  std::mt19937 rng(12345);
  for (const std::string& f : files) {
    std::vector<unsigned char> bytes = read_bytes(f);
    ASSERT_FALSE(bytes.empty()) << f;
    const std::string name = fs::path(f).filename().string();
    const size_t n = bytes.size();
    const size_t step = n <= 4096 ? 1 : n / 300;
    for (size_t len = 0; len <= n; len += step) {
      ImportResult r = import_memory(name, bytes.data(), len);
      expect_clean(r, name);
      if (::testing::Test::HasFatalFailure()) return;
    }
    for (int trial = 0; trial < 200; ++trial) {
      std::vector<unsigned char> d = bytes;
      for (int k = 0; k < 1 + trial % 8; ++k) {
        size_t at = rng() % d.size();
        const unsigned char pick[] = {0, 0xff, '-', '9', ' ', '\n', '\r', '#', '/', '\\', 0x7f};
        d[at] = trial % 2 ? pick[rng() % sizeof pick] : (unsigned char)(rng());
      }
      ImportResult r = import_memory(name, d.data(), d.size());
      expect_clean(r, name);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
}

}  // namespace
