// The bad-input table (issue #9): every `stairplan` sub-command, fed malformed, truncated, NaN,
// huge, empty and wrong-type inputs, exits 2 with a message naming the file (and the line or field
// where there is one), leaves no output file behind, prints no partial result, and never crashes
// or hangs (each run is under `timeout 60`). Sub-commands not in this build are skipped with a WARN.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mesh_files.h"
#include "test_paths.h"

using namespace stairplan::testing;
namespace fs = std::filesystem;

namespace {

struct BadCase {
  std::string label;             ///< kind of bad input: malformed, truncated, nan, huge, empty, wrong-type
  std::string command;           ///< the sub-command, e.g. "plan" or "qp"
  std::string file;              ///< name of the bad file written into the case's folder ("" for none)
  std::string contents;          ///< its bytes
  std::string args;              ///< arguments after `stairplan`; {dir} and {file} are replaced
  std::vector<std::string> must_name;  ///< stderr contains each of these ({dir}/{file} replaced)
  std::vector<std::string> outputs;    ///< paths under {dir} that must not exist afterwards
};

std::string Replace(std::string text, const std::string& dir, const std::string& file) {
  for (std::size_t at; (at = text.find("{dir}")) != std::string::npos;) text.replace(at, 5, dir);
  for (std::size_t at; (at = text.find("{file}")) != std::string::npos;) text.replace(at, 6, file);
  return text;
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// The commands this build's `stairplan --help` lists.
std::set<std::string> AvailableCommands() {
  const std::string dir = MakeTempDir("bad-input-help");
  RunCommand(BinDir() + "/stairplan --help", dir + "/help.out", dir + "/help.err");
  std::set<std::string> names;
  std::istringstream in(ReadFile(dir + "/help.out"));
  bool listing = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("commands:", 0) == 0) listing = true;
    if (!listing || line.size() < 3 || line[0] != ' ') continue;
    std::istringstream words(line);
    std::string name;
    words >> name;
    names.insert(name);
  }
  return names;
}

const char* kUrdfMalformed = "<robot name=\"r\"><link name=\"base\"><visual></link></robot>\n";
// Issue #28: bytes that are not UTF-8 never reach an XML parser; an unclosed element is named.
const char* kUrdfNotUtf8 = "<robot name=\"r\">\n<link name=\"b\xC6\xC6se\"/>\n</robot>\n";
const char* kUrdfCutCharacter = "<robot name=\"r\">\n<link name=\"base\"/>\n</robot>\xE6\xB7";
const char* kUrdfUnterminated = "<robot name=\"r\">\n<link name=\"base\">\n<visual/>\n";
const char* kYamlGood = "steps: 3\nrise: 0.17\nrun: 0.27\nnosing: 0.02\nwidth: 1.0\n";
const char* kQpsGood =
    "NAME          T\nROWS\n N  obj\n G  c1\nCOLUMNS\n    x1  obj  1.0  c1  1.0\n    x2  obj  1.0  c1  1.0\n"
    "RHS\n    rhs  c1  1.0\nBOUNDS\n UP bnd  x1  4.0\nQUADOBJ\n    x1  x1  2.0\n    x2  x2  2.0\nENDATA\n";
const char* kPlyHeader = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
const char* kCsvGood = "t,leg,x,y,z\n0.0,LF,0.3,0.15,0.0\n0.5,RF,0.3,-0.15,0.0\n";
const char* kMergeHeader = "rise,run,nosing,steps,direction,status,valid\n";

std::string Truncate(const std::string& text, double fraction) {
  return text.substr(0, static_cast<std::size_t>(static_cast<double>(text.size()) * fraction));
}

// A small real plan.json (the fuzzer's seed) for the truncated and edited validate cases.
std::string GoodPlan() { return Slurp(SourceDir() + "/tests/fuzz/corpus/plan_json/minimal.json"); }

std::string EditPlan(const std::string& plan, const std::string& from, const std::string& to) {
  std::string out = plan;
  const std::size_t at = out.find(from);
  if (at != std::string::npos) out.replace(at, from.size(), to);
  return out;
}

// stairbot named in Latin-1: the name once reached plan.json and nlohmann's dump threw (exit 1).
std::string Latin1Stairbot() { return EditPlan(Slurp(SourceDir() + "/data/robots/stairbot.urdf"), "\"stairbot\"", "\"stair\xE9" "bot\""); }
// stairbot with its base's collision box replaced by the mesh `mesh` (relative to the URDF) at `scale`.
std::string MeshRobotUrdf(const std::string& mesh, const std::string& scale) {
  return EditPlan(Slurp(SourceDir() + "/data/robots/stairbot.urdf"), "<geometry><box size=\"0.70 0.20 0.12\"/></geometry>",
                  "<geometry><mesh filename=\"" + mesh + "\" scale=\"" + scale + "\"/></geometry>");
}

bool IsMeshFile(const std::string& file) {
  const std::string extension = fs::path(file).extension().string();
  return extension == ".stl" || extension == ".obj" || extension == ".dae";
}

std::vector<BadCase> Table() {
  const std::string plan = GoodPlan();
  const std::vector<std::string> plan_out = {"out/plan.json", "out/plan.json.tmp", "out/plan.svg", "out/plan.svg.tmp"};
  std::vector<BadCase> t;
  // plan: the robot URDF, the stairs YAML and the stair flags.
  t.push_back({"malformed", "plan", "r.urdf", kUrdfMalformed, "plan --robot {file} --out {dir}/out", {"{file}"}, plan_out});
  t.push_back({"empty", "plan", "r.urdf", "", "plan --robot {file} --out {dir}/out", {"{file}"}, plan_out});
  t.push_back({"wrong-type", "plan", "r.urdf", kYamlGood, "plan --robot {file} --out {dir}/out", {"{file}"}, plan_out});
  t.push_back({"missing", "plan", "", "", "plan --robot {dir}/absent.urdf --out {dir}/out", {"absent.urdf"}, plan_out});
  t.push_back({"malformed", "plan", "r.urdf", kUrdfNotUtf8, "plan --robot {file} --out {dir}/out", {"{file}: line 2", "not UTF-8"}, plan_out});
  t.push_back({"truncated", "plan", "r.urdf", kUrdfCutCharacter, "plan --robot {file} --out {dir}/out", {"{file}: line 3", "multi-byte"}, plan_out});
  t.push_back({"truncated", "plan", "r.urdf", kUrdfUnterminated, "plan --robot {file} --out {dir}/out", {"{file}: line 2", "<link> is never closed"}, plan_out});
  t.push_back({"wrong-type", "plan", "r.urdf", Latin1Stairbot(), "plan --robot {file} --out {dir}/out", {"{file}: line 5", "not UTF-8"}, plan_out});
  t.push_back({"malformed", "plan", "s.yaml", "steps: [3, 4\nrise: 0.17\n", "plan --stairs {file} --out {dir}/out", {"{file}"}, plan_out});
  t.push_back({"truncated", "plan", "s.yaml", "steps: 3\nrise: 0.17\nrun:", "plan --stairs {file} --out {dir}/out", {"{file}", "run"}, plan_out});
  t.push_back({"nan", "plan", "s.yaml", "steps: 3\nrise: .nan\n", "plan --stairs {file} --out {dir}/out", {"{file}", "rise"}, plan_out});
  t.push_back({"huge", "plan", "s.yaml", "steps: 1000000000\n", "plan --stairs {file} --out {dir}/out", {"{file}", "steps"}, plan_out});
  t.push_back({"huge", "plan", "s.yaml", "rise: 1e300\n", "plan --stairs {file} --out {dir}/out", {"{file}", "rise"}, plan_out});
  t.push_back({"empty", "plan", "s.yaml", "", "plan --stairs {file} --out {dir}/out", {"{file}"}, plan_out});
  t.push_back({"wrong-type", "plan", "s.yaml", "steps: 3\nrise: high\n", "plan --stairs {file} --out {dir}/out", {"{file}", "rise"}, plan_out});
  t.push_back({"wrong-type", "plan", "s.yaml", "[0.17, 0.27]\n", "plan --stairs {file} --out {dir}/out", {"{file}"}, plan_out});
  t.push_back({"nan", "plan", "", "", "plan --rise nan --out {dir}/out", {"--rise"}, plan_out});
  t.push_back({"huge", "plan", "", "", "plan --steps 99999999999 --out {dir}/out", {"--steps"}, plan_out});
  t.push_back({"wrong-type", "plan", "", "", "plan --run wide --out {dir}/out", {"--run"}, plan_out});
  t.push_back({"empty", "plan", "", "", "plan --direction '' --out {dir}/out", {"--direction"}, plan_out});

  // Collision meshes (issue #21): a bad mesh file is the case's file, and {dir}/r.urdf (written
  // beside it) is stairbot with that mesh as its base's collision.
  const auto box = stairplan::testing::BoxTriangles(Eigen::Vector3d::Constant(-0.1), Eigen::Vector3d::Constant(0.1));
  std::string cut_stl = stairplan::testing::BinaryStl(box);
  cut_stl.resize(cut_stl.size() / 2);
  t.push_back({"missing", "plan", "r.urdf", MeshRobotUrdf("meshes/absent.stl", "1 1 1"), "plan --robot {file} --out {dir}/out", {"{file}", "meshes/absent.stl"}, plan_out});
  t.push_back({"missing", "robot", "r.urdf", MeshRobotUrdf("package://nowhere/base.stl", "1 1 1"), "robot {file} --package-path {dir}", {"{file}", "package://nowhere/base.stl", "{dir}"}, {}});
  t.push_back({"truncated", "plan", "m.stl", cut_stl, "plan --robot {dir}/r.urdf --out {dir}/out", {"{file}", "truncated"}, plan_out});
  t.push_back({"empty", "plan", "m.obj", "", "plan --robot {dir}/r.urdf --out {dir}/out", {"{file}"}, plan_out});
  t.push_back({"empty", "robot", "m.dae", stairplan::testing::Dae({}, "Z_UP", 1.0), "robot {dir}/r.urdf --json", {"{file}", "no triangles"}, {}});
  t.push_back({"huge", "plan", "r.urdf", MeshRobotUrdf("m.stl", "1e9 1e9 1e9"), "plan --robot {file} --out {dir}/out", {"{file}", "m.stl", "scale"}, plan_out});
  t.push_back({"wrong-type", "robot", "m.stl", kYamlGood, "robot {dir}/r.urdf --json", {"{file}"}, {}});
  t.push_back({"malformed", "robot", "r.urdf", kUrdfMalformed, "robot {file} --json", {"{file}"}, {}});
  t.push_back({"wrong-type", "robot", "", "", "robot --mesh-collision fuzzy", {"--mesh-collision"}, {}});

  // validate: plan.json.
  t.push_back({"malformed", "validate", "p.json", "{\"robot\": {", "validate {file} --json", {"{file}"}, {}});
  t.push_back({"truncated", "validate", "p.json", Truncate(plan, 0.6), "validate {file} --json", {"{file}"}, {}});
  t.push_back({"nan", "validate", "p.json", EditPlan(plan, "\"cadence_s\":", "\"cadence_s\": NaN, \"x\":"), "validate {file} --json", {"{file}"}, {}});
  t.push_back({"huge", "validate", "p.json", EditPlan(plan, "\"steps\":", "\"steps\": 1e300, \"x\":"), "validate {file} --json", {"{file}", "steps"}, {}});
  t.push_back({"huge", "validate", "p.json", EditPlan(plan, "\"cadence_s\":", "\"hip_height_fraction\": 40, \"cadence_s\":"), "validate {file} --json", {"{file}", "hip_height_fraction"}, {}});
  t.push_back({"huge", "validate", "p.json", EditPlan(plan, "\"cadence_s\":", "\"cadence_s\": 1e400, \"x\":"), "validate {file} --json", {"{file}", "too large"}, {}});
  t.push_back({"empty", "validate", "p.json", "", "validate {file} --json", {"{file}"}, {}});
  t.push_back({"wrong-type", "validate", "p.json", EditPlan(plan, "\"cadence_s\":", "\"cadence_s\": \"fast\", \"x\":"), "validate {file} --json", {"{file}", "cadence_s"}, {}});
  t.push_back({"wrong-type", "validate", "p.json", kQpsGood, "validate {file} --json", {"{file}"}, {}});
  t.push_back({"malformed", "validate", "r.urdf", kUrdfMalformed, "validate " + SourceDir() + "/tests/fuzz/corpus/plan_json/minimal.json --robot {file} --json", {"{file}"}, {}});

  // sweep: the robot, the axes; the CSV and SVG must not appear.
  const std::vector<std::string> sweep_out = {"s.csv", "s.csv.tmp", "s.svg", "s.svg.tmp"};
  t.push_back({"malformed", "sweep", "r.urdf", kUrdfMalformed, "sweep --robot {file} --rise 0.17 --run 0.27 --csv {dir}/s.csv --svg {dir}/s.svg", {"{file}"}, sweep_out});
  t.push_back({"empty", "sweep", "r.urdf", "", "sweep --robot {file} --rise 0.17 --run 0.27 --csv {dir}/s.csv", {"{file}"}, sweep_out});
  t.push_back({"nan", "sweep", "", "", "sweep --rise nan:0.2:3 --run 0.27 --csv {dir}/s.csv", {"--rise"}, sweep_out});
  t.push_back({"huge", "sweep", "", "", "sweep --rise 0.1:0.2:1000000000000 --run 0.27 --csv {dir}/s.csv", {"--rise"}, sweep_out});
  t.push_back({"truncated", "sweep", "", "", "sweep --rise 0.1:0.2 --run 0.27 --csv {dir}/s.csv", {"--rise"}, sweep_out});
  t.push_back({"wrong-type", "sweep", "", "", "sweep --steps many --csv {dir}/s.csv", {"--steps"}, sweep_out});
  t.push_back({"empty", "sweep", "", "", "sweep --direction '' --rise 0.17 --run 0.27 --csv {dir}/s.csv", {"--direction"}, sweep_out});

  // view: plan.json, the simulation's frames, a validation report; the page must not appear.
  const std::vector<std::string> view_out = {"v.html", "v.html.tmp"};
  const std::string view = "view " + SourceDir() + "/tests/fuzz/corpus/plan_json/minimal.json --html {dir}/v.html ";
  const std::string sim_frame = "{\"frames\": [{\"t\": 0, \"roll_pitch_yaw\": [0, 0, 0], \"base\": ";
  t.push_back({"malformed", "view", "p.json", "{\"robot\": {", "view {file} --html {dir}/v.html", {"{file}"}, view_out});
  t.push_back({"missing", "view", "", "", "view {dir}/absent.json --html {dir}/v.html", {"absent.json"}, view_out});
  t.push_back({"truncated", "view", "sim.json", sim_frame, view + "--sim {file}", {"{file}"}, view_out});
  t.push_back({"wrong-type", "view", "sim.json", sim_frame + "[0, 0]}]}", view + "--sim {file}", {"{file}", "frames[0].base"}, view_out});
  t.push_back({"nan", "view", "sim.json", sim_frame + "[0, 0, NaN]}]}", view + "--sim {file}", {"{file}"}, view_out});
  t.push_back({"empty", "view", "r.json", "", view + "--validation {file}", {"{file}"}, view_out});
  t.push_back({"wrong-type", "view", "r.json", "{\"ok\": false, \"violations\": [{\"t\": \"soon\"}]}", view + "--validation {file}",
               {"{file}", "violations[0].t"}, view_out});

  // sweep-merge: shard CSVs; the merged CSV must not appear.
  const std::vector<std::string> merge_out = {"m.csv", "m.csv.tmp"};
  t.push_back({"malformed", "sweep-merge", "a.csv", "rise,run\n0.1\n\"", "sweep-merge --csv {dir}/m.csv {file}", {"{file}"}, merge_out});
  t.push_back({"truncated", "sweep-merge", "a.csv", "rise,run,nos", "sweep-merge --csv {dir}/m.csv {file}", {"{file}"}, merge_out});
  t.push_back({"empty", "sweep-merge", "a.csv", "", "sweep-merge --csv {dir}/m.csv {file}", {"{file}"}, merge_out});
  t.push_back({"wrong-type", "sweep-merge", "a.csv", kQpsGood, "sweep-merge --csv {dir}/m.csv {file}", {"{file}"}, merge_out});
  t.push_back({"nan", "sweep-merge", "a.csv", std::string(kMergeHeader) + "nan,nan,nan,nan,up,ok,1\n", "sweep-merge --csv {dir}/m.csv {file}", {"{file}"}, merge_out});
  t.push_back({"missing", "sweep-merge", "", "", "sweep-merge --csv {dir}/m.csv {dir}/absent.csv", {"absent.csv"}, merge_out});

  // qp: QPS files for solve and bench; bench's CSV must not appear.
  t.push_back({"malformed", "qp", "q.qps", "NAME T\nROWS\n N obj\nCOLUMNS\n x1 obj\nENDATA\n", "qp solve {file} --json", {"{file}"}, {}});
  t.push_back({"truncated", "qp", "q.qps", Truncate(kQpsGood, 0.5), "qp solve {file} --json", {"{file}"}, {}});
  t.push_back({"nan", "qp", "q.qps", EditPlan(kQpsGood, "c1  1.0\nBOUNDS", "c1  nan\nBOUNDS"), "qp solve {file} --json", {"{file}"}, {}});
  t.push_back({"huge", "qp", "q.qps", EditPlan(kQpsGood, "c1  1.0\nBOUNDS", "c1  1e400\nBOUNDS"), "qp solve {file} --json", {"{file}"}, {}});
  t.push_back({"empty", "qp", "q.qps", "", "qp solve {file} --json", {"{file}"}, {}});
  t.push_back({"wrong-type", "qp", "q.qps", kYamlGood, "qp solve {file} --json", {"{file}"}, {}});
  t.push_back({"malformed", "qp", "q.qps", "NAME T\nROWS\n N obj\nCOLUMNS\n x1 obj\nENDATA\n", "qp bench {file} --csv {dir}/b.csv", {"{file}"}, {"b.csv", "b.csv.tmp"}});
  t.push_back({"nan", "qp", "", "", "qp solve {dir}/absent.qps --time-limit nan", {"--time-limit"}, {}});
  t.push_back({"huge", "qp", "seq/dims.oqp", "1e300 2 1 0\n", "qp bench {dir}/seq --csv {dir}/b.csv", {"dims.oqp"}, {"b.csv", "b.csv.tmp"}});
  t.push_back({"huge", "qp", "seq/dims.oqp", "100000 100000 100000 0\n", "qp bench {dir}/seq --csv {dir}/b.csv", {"dims.oqp"}, {"b.csv", "b.csv.tmp"}});
  t.push_back({"huge", "validate", "p.json", EditPlan(plan, "\"stair_index\":", "\"stair_index\": 1e300, \"x0\":"), "validate {file} --json", {"{file}", "stair_index"}, {}});
  t.push_back({"huge", "validate", "p.json", EditPlan(plan, "\"cadence_s\":", "\"schema_version\": 99, \"cadence_s\":"), "validate {file} --json", {"{file}", "schema_version"}, {}});

  // gait-design: flags only.
  const std::string gait = "gait-design --json --run 0.27 --lmax 0.6 --body-length 0.6 ";
  t.push_back({"nan", "gait-design", "", "", gait + "--rise nan", {"--rise"}, {}});
  t.push_back({"huge", "gait-design", "", "", gait + "--rise 1e400", {"--rise"}, {}});
  t.push_back({"wrong-type", "gait-design", "", "", gait + "--rise tall", {"--rise"}, {}});
  t.push_back({"empty", "gait-design", "", "", gait + "--rise ''", {"--rise"}, {}});
  t.push_back({"malformed", "gait-design", "", "", gait + "--rise 0.17 --tread-errors 0.01,,x", {"--tread-errors"}, {}});
  t.push_back({"truncated", "gait-design", "", "", "gait-design --json --rise 0.17", {"--run"}, {}});

  // map: point clouds (PLY, XYZ); the SVG must not appear.
  const std::vector<std::string> map_out = {"m.svg", "m.svg.tmp"};
  const std::string map = "map --json --svg {dir}/m.svg --cloud {file}";
  t.push_back({"malformed", "map", "c.ply", "ply\nformat ascii 1.0\nelement vertex three\nend_header\n", map, {"{file}"}, map_out});
  t.push_back({"truncated", "map", "c.ply", std::string(kPlyHeader) + "0 0 0\n0.1 0", map, {"{file}"}, map_out});
  t.push_back({"truncated", "map", "c.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty double x\nproperty double y\nproperty double z\nend_header\n\x01\x02\x03", map, {"{file}"}, map_out});
  t.push_back({"nan", "map", "c.ply", std::string(kPlyHeader) + "0 0 0\nnan 0 0\n0.2 0 0.17\n", map, {"{file}"}, map_out});
  t.push_back({"huge", "map", "c.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty double x\nproperty double y\nproperty double z\nend_header\n", map, {"{file}"}, map_out});
  t.push_back({"empty", "map", "c.ply", "", map, {"{file}"}, map_out});
  t.push_back({"wrong-type", "map", "c.ply", kYamlGood, map, {"{file}"}, map_out});
  t.push_back({"malformed", "map", "c.xyz", "0 0 0\n0.1 zero 0\n", map, {"{file}", "2"}, map_out});
  t.push_back({"nan", "map", "c.xyz", "0 0 0\n0.1 0 nan\n", map, {"{file}", "2"}, map_out});
  t.push_back({"huge", "map", "c.xyz", "0 0 0\n1e400 0 0\n", map, {"{file}", "2"}, map_out});
  t.push_back({"empty", "map", "c.xyz", "", map, {"{file}"}, map_out});
  t.push_back({"wrong-type", "map", "c.xyz", kCsvGood, map, {"{file}"}, map_out});
  t.push_back({"huge", "map", "c.xyz", "0 0 0\n0.1 0 0\n0.2 0 0.17\n", "map --json --resolution 1e-9 --svg {dir}/m.svg --cloud {file}", {"--resolution"}, map_out});
  // map and plan --cloud: PCD clouds (header, binary data, LZF block).
  using namespace std::string_literals;
  const auto pcd = [](const std::string& points, const std::string& data) {
    return "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " + points + "\nHEIGHT 1\nPOINTS " + points +
           "\nDATA " + data + "\n";
  };
  t.push_back({"malformed", "map", "c.pcd", "VERSION 0.7\nFIELDS x y z rgb\nSIZE 4 4 4\nTYPE F F F U\nPOINTS 1\nDATA ascii\n1 2 3 4\n", map, {"{file}", "SIZE"}, map_out});
  t.push_back({"truncated", "map", "c.pcd", pcd("10", "binary") + "\x01\x02\x03\x04\x05\x06\x07", map, {"{file}", "DATA binary"}, map_out});
  t.push_back({"malformed", "map", "c.pcd", pcd("1", "binary_compressed") + "\x03\0\0\0\x0c\0\0\0\x3f\0\0"s, map, {"{file}", "binary_compressed", "corrupt"}, map_out});
  t.push_back({"nan", "map", "c.pcd", pcd("2", "ascii") + "nan nan nan\nnan 0 nan\n", map, {"{file}", "no finite points"}, map_out});
  t.push_back({"huge", "map", "c.pcd", pcd("4000000000", "binary_compressed") + "\x03\0\0\0\x0c\0\0\0\x3f\0\0"s, map, {"{file}", "POINTS"}, map_out});
  t.push_back({"empty", "map", "c.pcd", "", map, {"{file}"}, map_out});
  t.push_back({"wrong-type", "map", "c.pcd", kYamlGood, map, {"{file}"}, map_out});
  t.push_back({"truncated", "plan", "c.pcd", pcd("10", "binary") + "\x01\x02", "plan --cloud {file} --out {dir}/out", {"{file}", "DATA binary"}, plan_out});

  // footfalls: CSV.
  t.push_back({"malformed", "footfalls", "f.csv", "t,leg,x,y,z\n0.0,LF,0.3;0.15;0\n", "footfalls --json {file}", {"{file}", "line 2"}, {}});
  t.push_back({"truncated", "footfalls", "f.csv", "t,leg,x,y,z\n0.0,LF,0.3,0.15,0.0\n0.5,RF,0.3,", "footfalls --json {file}", {"{file}", "line 3"}, {}});
  t.push_back({"nan", "footfalls", "f.csv", "t,leg,x,y,z\n0.0,LF,nan,0.15,0.0\n", "footfalls --json {file}", {"{file}", "line 2"}, {}});
  t.push_back({"huge", "footfalls", "f.csv", "t,leg,x,y,z\n0.0,LF,1e400,0.15,0.0\n", "footfalls --json {file}", {"{file}", "line 2"}, {}});
  t.push_back({"empty", "footfalls", "f.csv", "", "footfalls --json {file}", {"{file}"}, {}});
  t.push_back({"wrong-type", "footfalls", "f.csv", "t,leg,x,y,z\nzero,LF,0.3,0.15,0.0\n", "footfalls --json {file}", {"{file}", "line 2"}, {}});
  t.push_back({"wrong-type", "footfalls", "f.csv", kPlyHeader, "footfalls --json {file}", {"{file}"}, {}});

  // robustness (when present): robot and stair flags.
  t.push_back({"malformed", "robustness", "r.urdf", kUrdfMalformed, "robustness --json --robot {file}", {"{file}"}, {}});
  t.push_back({"nan", "robustness", "", "", "robustness --json --sigma-rise nan", {"--sigma-rise"}, {}});
  t.push_back({"huge", "robustness", "", "", "robustness --json --trials 99999999999", {"--trials"}, {}});
  t.push_back({"wrong-type", "robustness", "", "", "robustness --json --rise steep", {"--rise"}, {}});
  t.push_back({"wrong-type", "robustness", "f.txt", "a file", "robustness --json --trials 1 --stairs-out {file}/sub", {"--stairs-out"}, {}});

  // simulate (when present): plan.json.
  t.push_back({"malformed", "simulate", "p.json", "{\"robot\": {", "simulate {file}", {"{file}"}, {}});
  t.push_back({"truncated", "simulate", "p.json", Truncate(plan, 0.5), "simulate {file}", {"{file}"}, {}});
  t.push_back({"empty", "simulate", "p.json", "", "simulate {file}", {"{file}"}, {}});
  t.push_back({"wrong-type", "simulate", "p.json", EditPlan(plan, "\"cadence_s\":", "\"cadence_s\": \"fast\", \"x\":"), "simulate {file}", {"{file}", "cadence_s"}, {}});
  return t;
}

}  // namespace

TEST_CASE("every sub-command refuses bad input with exit 2, a message naming it, and no output", "[hardening][cli]") {
  const std::set<std::string> available = AvailableCommands();
  REQUIRE(available.count("plan") == 1);
  const std::vector<BadCase> table = Table();
  std::set<std::string> skipped, covered;
  int index = 0;
  for (const BadCase& c : table) {
    ++index;
    if (available.count(c.command) == 0) {
      skipped.insert(c.command);
      continue;
    }
    covered.insert(c.command);
    const std::string dir = MakeTempDir("bad-input-" + std::to_string(index));
    const std::string file = c.file.empty() ? std::string() : dir + "/" + c.file;
    if (!file.empty()) {
      fs::create_directories(fs::path(file).parent_path());
      std::ofstream(file, std::ios::binary) << c.contents;
      if (IsMeshFile(c.file)) std::ofstream(dir + "/r.urdf") << MeshRobotUrdf(c.file, "1 1 1");
    }
    const std::string args = Replace(c.args, dir, file);
    const int code = RunCommand("timeout 60 " + BinDir() + "/stairplan " + args, dir + "/run.out", dir + "/run.err");
    const std::string out = ReadFile(dir + "/run.out");
    const std::string err = ReadFile(dir + "/run.err");
    INFO("case " << index << " (" << c.label << "): stairplan " << args << "\nstderr: " << err << "\nstdout: " << out.substr(0, 400));
    CHECK(code == 2);  // 124 is a hang (timeout), 1 a sanitizer report or an unexpected exception
    CHECK(err.find("runtime error") == std::string::npos);
    CHECK(err.find("Sanitizer") == std::string::npos);
    for (const std::string& name : c.must_name) CHECK_THAT(err, Catch::Contains(Replace(name, dir, file)));
    // No partial JSON result on stdout. `qp solve` on data the solver refuses (NaN, an impossible
    // bound) is the exception: its JSON is the whole result, status "invalid_input" (exit 2).
    const bool status_result = !c.file.empty() && c.args.rfind("qp solve", 0) == 0 && (c.label == "nan" || c.label == "huge");
    if (status_result) {
      CHECK_THAT(out, Catch::Contains("\"invalid_input\""));
    } else {
      CHECK(out.find('{') == std::string::npos);
    }
    for (const std::string& output : c.outputs) {
      INFO("output " << output);
      CHECK_FALSE(fs::exists(dir + "/" + output));
    }
  }
  for (const std::string& name : skipped) WARN("stairplan " << name << " is not in this build: its bad-input rows were skipped");
  // Every sub-command this build has must have rows in the table.
  for (const std::string& name : available) {
    INFO("sub-command without bad-input rows: " << name);
    CHECK(covered.count(name) == 1);
  }
}
