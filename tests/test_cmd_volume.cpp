// `geombake volume`, run as a process: real files in, an OBJ out that is a
// closed oriented mesh; bad input gives `Error:` naming the problem, a
// non-zero exit and no output file.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kBake = std::string(GEOM_BINARY_DIR) + "/tools/geombake";
const std::string kOut = std::string(GEOM_BINARY_DIR) + "/test_cmd_volume_out";

struct Outcome {
  int code;
  std::string output;  // stdout and stderr
};

Outcome run(const std::string& args) {
  Outcome r{-1, ""};
  FILE* p = popen((kBake + " volume " + args + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

bool exists(const std::string& path) { return std::ifstream(path).good(); }

struct Obj {
  std::vector<double> v;
  std::vector<uint32_t> f;
  std::string header;
};

Obj read_obj(const std::string& path) {
  Obj o;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "#") o.header += line + "\n";
    if (tag == "v") {
      double x, y, z;
      s >> x >> y >> z;
      o.v.insert(o.v.end(), {x, y, z});
    }
    if (tag == "f") {
      uint32_t a, b, c;
      s >> a >> b >> c;
      o.f.insert(o.f.end(), {a - 1, b - 1, c - 1});
    }
  }
  return o;
}

// Every directed edge matched by its reverse, as often: closed and oriented.
bool closed(const Obj& o) {
  std::map<std::pair<uint32_t, uint32_t>, int> e;
  for (size_t t = 0; t < o.f.size(); t += 3)
    for (int k = 0; k < 3; ++k) ++e[{o.f[t + k], o.f[t + (k + 1) % 3]}];
  for (auto& x : e) {
    auto it = e.find({x.first.second, x.first.first});
    if (it == e.end() || it->second != x.second) return false;
  }
  return true;
}

TEST(CmdVolume, RealFilesGiveClosedVolumes) {
  const std::string assimp = "/usr/share/assimp/models/";
  const std::string draco = std::string(GEOM_TEST_DATA) + "/draco/";
  struct Case {
    std::string file, light;
  };
  const std::vector<Case> cases = {
      {assimp + "OBJ/box.obj", "2,3,4,1"},
      {assimp + "OBJ/box.obj", "0.3,1,0.2,0"},
      {assimp + "OBJ/WusonOBJ.obj", "1,5,2,1"},
      {assimp + "glTF2/BoxTextured-glTF/BoxTextured.gltf", "-1,2,0.5,0"},
      {draco + "non_manifold_wrap.obj", "0.5,3,0.2,1"},
      {draco + "deg_faces.obj", "1,2,3,1"},
      {std::string(GEOM_SOURCE_DIR) + "/data/default_scene.gltf", "1,6,2,1"},
  };
  for (const Case& c : cases) {
    ASSERT_TRUE(exists(c.file)) << c.file << " is missing (assimp-testmodels: scripts/setup.sh)";
    const std::string out = kOut + ".obj";
    std::remove(out.c_str());
    const Outcome r = run("'" + c.file + "' --light " + c.light + " -o '" + out + "' -v");
    ASSERT_EQ(r.code, 0) << c.file << "\n" << r.output;
    EXPECT_NE(r.output.find("light '--light'"), std::string::npos) << r.output;
    const Obj o = read_obj(out);
    // The header: each line of the comment a "# " line, then the vertices.
    std::ifstream text(out);
    const std::string obj((std::istreambuf_iterator<char>(text)), std::istreambuf_iterator<char>());
    EXPECT_EQ(obj.rfind("# shadow volume of " + c.file + "\n# light ", 0), 0u) << obj.substr(0, 200);
    EXPECT_EQ(obj.find("\nv "), o.header.size() - 1) << o.header;
    EXPECT_FALSE(o.f.empty()) << c.file;
    EXPECT_TRUE(closed(o)) << c.file;
    EXPECT_NE(o.header.find(c.light.substr(0, 2)), std::string::npos);
    for (double x : o.v) ASSERT_TRUE(std::isfinite(x));
    // No caps: what depth-pass draws, sides only (open at the mesh).
    const Outcome s = run("'" + c.file + "' --light " + c.light + " --no-caps -o '" + out + "'");
    EXPECT_EQ(s.code, 0) << s.output;
  }
}

TEST(CmdVolume, BadInputSaysErrorAndWritesNothing) {
  const std::string out = kOut + "_bad.obj";
  const std::string box = "/usr/share/assimp/models/OBJ/box.obj";
  const std::string draco = std::string(GEOM_TEST_DATA) + "/draco/";
  struct Case {
    std::string args, says;
  };
  std::vector<Case> cases = {
      {"/no/such/file.obj --light 1,2,3,1", "/no/such/file.obj"},
      {"'" + box + "' --light 1,2,3", "--light"},
      {"'" + box + "' --light 1,2,3,0.5", "--light"},
      {"'" + box + "' --light 0,0,0,0", "--light"},
      {"'" + box + "' --light nan,0,0,1", "--light"},
      {"'" + box + "' --light 1,2,3,1 --extrude-distance -4", "--extrude-distance"},
      {"'" + box + "' --light 1,2,3,1 --bogus", "--bogus"},
      {"'" + box + "'", "--light"},
      {"'" + draco + "inf_nan.obj' --light 1,2,3,1", "inf_nan.obj"},
      {"/usr/share/assimp/models/invalid/malformed.obj --light 1,2,3,1", "malformed.obj"},
      {"/usr/share/assimp/models/invalid/OutOfMemory.off --light 1,2,3,1", "OutOfMemory.off"},
      {"/usr/share/assimp/models/glTF2/MissingBin/BoxTextured.gltf --light 1,2,3,1", "BoxTextured"},
      {"/usr/share/assimp/models/glTF2/RecursiveNodes/RecursiveNodes.gltf --light 1,2,3,1", "RecursiveNodes"},
  };
  for (const Case& c : cases) {
    std::remove(out.c_str());
    const Outcome r = run(c.args + " -o '" + out + "'");
    EXPECT_NE(r.code, 0) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find("Error:"), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(exists(out)) << c.args;
  }
  // An unwritable output: an error, no file.
  const Outcome r = run("'" + box + "' --light 1,2,3,1 -o /no/such/dir/v.obj");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("Error:"), std::string::npos) << r.output;
}

}  // namespace
