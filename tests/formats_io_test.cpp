// Contour file formats: round trips, repairs, the catalogue of malformed files, real CSL data
// and the convert command.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "modeling/contour_io.h"
#include "modeling/section_validate.h"

using namespace ps;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("planesketch-formats-io-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

// Two planes (one oblique), an outer square with a square hole, and a triangle.
SectionSet sample_set() {
  SectionSet s;
  s.units = "mm";
  s.planes.push_back(Plane{Vec3(0, 0, 1), 0.25});
  s.planes.push_back(Plane{Vec3(0.6, 0.8, 0), -3.0});
  auto on_z = [](double x, double y) { return Vec3(x, y, 0.25); };
  s.curves.push_back({0, {on_z(0, 0), on_z(4, 0), on_z(4, 4), on_z(0, 4)}});
  s.curves.push_back({0, {on_z(1, 1), on_z(1, 3), on_z(3, 3), on_z(3, 1)}});
  // On plane 1: points p with 0.6x + 0.8y = -3: base (-1.8, -2.4, 0), in-plane direction (0.8, -0.6, 0).
  const Vec3 b(-1.8, -2.4, 0), t(0.8, -0.6, 0), z(0, 0, 1);
  s.curves.push_back({1, {b, b + 2 * t, b + t + 1.5 * z}});
  return s;
}

void expect_same(const SectionSet& a, const SectionSet& b, double tol) {
  ASSERT_EQ(a.planes.size(), b.planes.size());
  ASSERT_EQ(a.curves.size(), b.curves.size());
  for (std::size_t i = 0; i < a.planes.size(); ++i) {
    EXPECT_LE((a.planes[i].normal - b.planes[i].normal).norm(), tol);
    EXPECT_NEAR(a.planes[i].offset, b.planes[i].offset, tol);
  }
  for (std::size_t c = 0; c < a.curves.size(); ++c) {
    EXPECT_EQ(a.curves[c].plane, b.curves[c].plane);
    ASSERT_EQ(a.curves[c].points.size(), b.curves[c].points.size()) << "curve " << c;
    for (std::size_t k = 0; k < a.curves[c].points.size(); ++k)
      EXPECT_LE((a.curves[c].points[k] - b.curves[c].points[k]).norm(), tol) << "curve " << c << " point " << k;
  }
}

Result<SectionSet> parse(const std::string& text, ContourFormat f, std::vector<std::string>* w = nullptr) {
  return parse_sections(text, f, "test", w);
}

}  // namespace

// === Round trips
TEST(FormatsIo, RoundTripAllFormatsThroughFiles) {
  SectionSet s = sample_set();
  ASSERT_TRUE(finish_sections(s, "sample"));
  const fs::path d = temp_dir();
  for (const char* ext : {".json", ".csl", ".contour"}) {
    const fs::path p = d / (std::string("sample") + ext);
    ASSERT_TRUE(write_sections(p.string(), s)) << ext;
    std::vector<std::string> w;
    auto r = read_sections(p.string(), &w);
    ASSERT_TRUE(r) << r.message();
    EXPECT_TRUE(w.empty()) << ext << ": " << w.front();
    expect_same(s, *r, 0.0);  // shortest round-trip numbers: bit-identical
    if (std::string(ext) == ".json") {
      EXPECT_EQ(r->units, "mm");
    }
  }
}

TEST(FormatsIo, CslMarksTheInnerSquareAsAHoleOfTheOuter) {
  SectionSet s = sample_set();
  ASSERT_TRUE(finish_sections(s, "sample"));
  const std::string csl = format_csl(s);
  EXPECT_NE(csl.find("\n4h0 1 4 5 6 7\n"), std::string::npos) << csl;
  EXPECT_NE(csl.find("\n4 1 0 1 2 3\n"), std::string::npos) << csl;
}

// Multi-material CSL (Abdomen): labelled components nested without a hole flag, or
// overlapping, are one object, the union of the labels (curve_repair.h, read_csl_labels).
TEST(FormatsIo, CslLabelsNestedWithoutHoleFlagAreOneMaterial) {
  const std::string head = "CSLC\n1 2\n\n1 8 2 0 0 1 -0.5\n0 0 0.5\n4 0 0.5\n4 4 0.5\n0 4 0.5\n";
  auto area2 = [](const SectionSet& s, std::size_t c) {
    double a = 0.0;
    const auto& p = s.curves[c].points;
    for (std::size_t i = 0; i < p.size(); ++i)
      a += p[i].x() * p[(i + 1) % p.size()].y() - p[i].y() * p[(i + 1) % p.size()].x();
    return std::abs(0.5 * a);
  };
  {  // an organ inside another, no hole flag: the outer one alone bounds the object
    std::vector<std::string> w;
    auto r = parse(head + "1 1 0.5\n2 1 0.5\n2 2 0.5\n1 2 0.5\n\n4 1 0 1 2 3\n4 2 4 5 6 7\n", ContourFormat::Csl, &w);
    ASSERT_TRUE(r) << r.message();
    ASSERT_EQ(r->curves.size(), 1u);
    EXPECT_DOUBLE_EQ(area2(*r, 0), 16.0);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("plane 1: 2 components nest or overlap"), std::string::npos) << w[0];
    EXPECT_EQ(r->curves[0].points[0], Vec3(0, 0, 0.5));  // input points kept bit for bit
  }
  {  // the same square flagged as a hole: read as it is
    std::vector<std::string> w;
    auto r = parse(head + "1 1 0.5\n2 1 0.5\n2 2 0.5\n1 2 0.5\n\n4 1 0 1 2 3\n4h0 1 4 5 6 7\n", ContourFormat::Csl, &w);
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(r->curves.size(), 2u);
    EXPECT_TRUE(w.empty());
  }
  {  // two materials overlapping: their union
    std::vector<std::string> w;
    auto r = parse(head + "3 3 0.5\n6 3 0.5\n6 6 0.5\n3 6 0.5\n\n4 1 0 1 2 3\n4 2 4 5 6 7\n", ContourFormat::Csl, &w);
    ASSERT_TRUE(r) << r.message();
    ASSERT_EQ(r->curves.size(), 1u);
    EXPECT_DOUBLE_EQ(area2(*r, 0), 16.0 + 9.0 - 1.0);
    auto v = validate_sections(*r);
    EXPECT_TRUE(v) << v.message();
  }
  {  // one material crossing itself: a tracing error, read as it is (validation refuses it)
    std::vector<std::string> w;
    auto r = parse(head + "3 3 0.5\n6 3 0.5\n6 6 0.5\n3 6 0.5\n\n4 1 0 1 2 3\n4 1 4 5 6 7\n", ContourFormat::Csl, &w);
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(r->curves.size(), 2u);
    EXPECT_FALSE(validate_sections(*r));
  }
}

TEST(FormatsIo, RoundTripIsStableUnderRepeatedConversion) {
  SectionSet s = sample_set();
  ASSERT_TRUE(finish_sections(s, "sample"));
  std::string json = format_contour_json(s);
  for (int i = 0; i < 3; ++i) {
    auto a = parse(json, ContourFormat::Json);
    ASSERT_TRUE(a) << a.message();
    auto b = parse(format_csl(*a), ContourFormat::Csl);
    ASSERT_TRUE(b) << b.message();
    auto c = parse(format_ctr2suf(*b), ContourFormat::Ctr2Suf);
    ASSERT_TRUE(c) << c.message();
    c->units = s.units;
    EXPECT_EQ(format_contour_json(*c), json);
    json = format_contour_json(*c);
  }
}

// === Repairs and metamorphic properties
TEST(FormatsIo, NormalIsNormalisedAndOffsetScaledAlike) {
  const std::string a = R"({"planes":[{"normal":[0,0,2],"offset":1}],"curves":[{"plane":0,"points":[[0,0,0.5],[1,0,0.5],[0,1,0.5]]}]})";
  const std::string b = R"({"planes":[{"normal":[0,0,-4e-30],"offset":-2e-30}],"curves":[{"plane":0,"points":[[0,0,0.5],[1,0,0.5],[0,1,0.5]]}]})";
  auto ra = parse(a, ContourFormat::Json), rb = parse(b, ContourFormat::Json);
  ASSERT_TRUE(ra) << ra.message();
  ASSERT_TRUE(rb) << rb.message();
  EXPECT_EQ(ra->planes[0].normal, Vec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(ra->planes[0].offset, 0.5);
  EXPECT_EQ(rb->planes[0].normal, Vec3(0, 0, -1));
  EXPECT_DOUBLE_EQ(rb->planes[0].offset, -0.5);
}

TEST(FormatsIo, OffPlanePointsAreProjectedSilentlyWarnedOrRefused) {
  auto make = [](double dz) {
    std::ostringstream s;
    s.precision(17);
    s << R"({"planes":[{"normal":[0,0,1],"offset":0}],"curves":[{"plane":0,"points":[[0,0,0],[10,0,0],[10,10,)" << dz
      << R"(],[0,10,0]]}]})";
    return s.str();
  };
  const double diag = std::sqrt(200.0);
  std::vector<std::string> w;
  auto silent = parse(make(0.5e-6 * diag), ContourFormat::Json, &w);
  ASSERT_TRUE(silent) << silent.message();
  EXPECT_TRUE(w.empty());
  EXPECT_EQ(silent->curves[0].points[2].z(), 0.0);
  auto warned = parse(make(0.5e-3 * diag), ContourFormat::Json, &w);
  ASSERT_TRUE(warned) << warned.message();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("projected onto it"), std::string::npos) << w[0];
  EXPECT_EQ(warned->curves[0].points[2].z(), 0.0);
  auto refused = parse(make(2e-3 * diag), ContourFormat::Json);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("test: curve 0 (plane 0): point 2 lies"), std::string::npos) << refused.message();
}

TEST(FormatsIo, RepeatedFirstPointIsDroppedWithAWarning) {
  std::vector<std::string> w;
  auto r = parse(R"({"planes":[{"normal":[0,0,1],"offset":0}],"curves":[{"plane":0,"points":[[0,0,0],[1,0,0],[1,1,0],[0,0,0]]}]})",
                 ContourFormat::Json, &w);
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->curves[0].points.size(), 3u);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("first point repeated"), std::string::npos);
}

TEST(FormatsIo, CoincidentPlanesAreMergedAndCurvesReindexed) {
  std::vector<std::string> w;
  auto r = parse(R"({"planes":[{"normal":[0,0,1],"offset":1},{"normal":[1,0,0],"offset":0},{"normal":[0,0,-2],"offset":-2}],
    "curves":[{"plane":2,"points":[[0,0,1],[1,0,1],[1,1,1]]},{"plane":1,"points":[[0,0,0],[0,1,0],[0,1,1]]}]})",
                 ContourFormat::Json, &w);
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->planes.size(), 2u);
  EXPECT_EQ(r->curves[0].plane, 0);
  EXPECT_EQ(r->curves[1].plane, 1);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("plane 2 coincides with plane 0"), std::string::npos) << w[0];
}

TEST(FormatsIo, UnknownKeysAreIgnoredAndNewerVersionsWarn) {
  std::vector<std::string> w;
  auto r = parse(R"({"version":2,"colour":"red","planes":[{"normal":[0,0,1],"offset":0,"name":"a"}],
    "curves":[{"plane":0,"points":[[0,0,0],[1,0,0],[1,1,0]],"pressure":[1,2,3]}]})", ContourFormat::Json, &w);
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("version is 2"), std::string::npos);
}

TEST(FormatsIo, HugeAndTinyCoordinatesReadExactly) {
  for (double scale : {1e30, 1e-30}) {
    SectionSet s;
    s.planes.push_back(Plane{Vec3(0, 0, 1), 3 * scale});
    s.curves.push_back({0, {Vec3(0, 0, 3 * scale), Vec3(scale, 0, 3 * scale), Vec3(scale, 2 * scale, 3 * scale)}});
    for (auto f : {ContourFormat::Json, ContourFormat::Csl, ContourFormat::Ctr2Suf}) {
      const std::string text = f == ContourFormat::Json ? format_contour_json(s) : f == ContourFormat::Csl ? format_csl(s) : format_ctr2suf(s);
      auto r = parse(text, f);
      ASSERT_TRUE(r) << scale << " " << r.message();
      expect_same(s, *r, 0.0);
    }
  }
}

TEST(FormatsIo, TranslatedAndScaledInputReadsTranslatedAndScaled) {
  SectionSet s = sample_set();
  ASSERT_TRUE(finish_sections(s, "sample"));
  SectionSet t = s;
  const Vec3 shift(5, -7, 11);
  const double k = 3.0;
  for (auto& p : t.planes) p.offset = k * p.offset + p.normal.dot(shift);
  for (auto& c : t.curves)
    for (auto& q : c.points) q = k * q + shift;
  auto r = parse(format_csl(t), ContourFormat::Csl);
  ASSERT_TRUE(r) << r.message();
  expect_same(t, *r, 1e-12);
}

TEST(FormatsIo, ReversedAndReorderedCurvesReadTheSameWay) {
  SectionSet s = sample_set();
  ASSERT_TRUE(finish_sections(s, "sample"));
  SectionSet t = s;
  std::reverse(t.curves.begin(), t.curves.end());
  for (auto& c : t.curves) std::reverse(c.points.begin(), c.points.end());
  auto r = parse(format_ctr2suf(t), ContourFormat::Ctr2Suf);
  ASSERT_TRUE(r) << r.message();
  // .contour groups by plane; each loop keeps its points and direction.
  ASSERT_EQ(r->curves.size(), 3u);
  EXPECT_EQ(r->curves[0].points, t.curves[1].points);
  EXPECT_EQ(r->curves[1].points, t.curves[2].points);
  EXPECT_EQ(r->curves[2].points, t.curves[0].points);
}

// === Format specifics
TEST(FormatsIo, CslToleratesBlankLinesTrailingSpacesCrLfAndEmptyPlanes) {
  const std::string text =
      "CSLC\r\n 2 2 \r\n\r\n 1 0 0 0.0 0.0 1.0 -1.0\r\n\r\n2 4 1 0 0 2 -4\r\n\r\n0 0 2 \r\n1 0 2\r\n1 1 2\r\n 0 1 2\r\n\r\n4 1 0 1 2 3 \r\n\r\n";
  auto r = parse(text, ContourFormat::Csl);
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->planes.size(), 2u);
  ASSERT_EQ(r->curves.size(), 1u);
  EXPECT_EQ(r->curves[0].plane, 1);
  EXPECT_DOUBLE_EQ(r->planes[1].offset, 2.0);
}

TEST(FormatsIo, CslWithFlippedPlaneSignIsReadWithAWarning) {
  // rose.csl writes Ax+By+Cz = D: points at z = -0.5 with "0 0 1 -0.5".
  std::vector<std::string> w;
  auto r = parse("CSLC\n1 2\n\n1 3 1 0 0 1 -0.5\n\n0 0 -0.5\n1 0 -0.5\n1 1 -0.5\n\n3 1 0 1 2\n", ContourFormat::Csl, &w);
  ASSERT_TRUE(r) << r.message();
  EXPECT_DOUBLE_EQ(r->planes[0].offset, -0.5);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("Ax+By+Cz = D"), std::string::npos);
}

TEST(FormatsIo, ContourEdgesInAnyOrderAndDirectionFormLoops) {
  // Two triangles on z = 1; edges shuffled and some reversed; labels on either side.
  const std::string text =
      "1\n0 0 2 2\n6 6\n0 0 1\n1 0 1\n0 1 1\n5 5 1\n6 5 1\n5 6 1\n"
      "4 5 0 1\n1 2 1 0\n3 4 1 0\n0 2 0 1\n5 3 1 0\n0 1 1 0\n";
  auto r = parse(text, ContourFormat::Ctr2Suf);
  ASSERT_TRUE(r) << r.message();
  ASSERT_EQ(r->curves.size(), 2u);
  EXPECT_EQ(r->curves[0].points.size(), 3u);
  EXPECT_EQ(r->curves[1].points.size(), 3u);
  EXPECT_DOUBLE_EQ(r->planes[0].offset, 1.0);
}

TEST(FormatsIo, ContourEdgesBetweenTwoInsideMaterialsAreIgnoredWithAWarning) {
  std::vector<std::string> w;
  auto r = parse("1\n0 0 1 0\n3 4\n0 0 0\n1 0 0\n1 1 0\n0 1 1 0\n1 2 1 0\n2 0 1 0\n0 2 1 2\n", ContourFormat::Ctr2Suf, &w);
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->curves.size(), 1u);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("ignored 1 edge"), std::string::npos);
}

TEST(FormatsIo, SniffingRecognisesEachFormat) {
  SectionSet s = sample_set();
  EXPECT_EQ(sniff_contour_format(format_contour_json(s)), ContourFormat::Json);
  EXPECT_EQ(sniff_contour_format(format_csl(s)), ContourFormat::Csl);
  EXPECT_EQ(sniff_contour_format(format_ctr2suf(s)), ContourFormat::Ctr2Suf);
  EXPECT_FALSE(sniff_contour_format("solid cube\n"));
  const fs::path d = temp_dir();
  spit(d / "no_extension", format_csl(s));
  auto r = read_sections((d / "no_extension").string());
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r->curves.size(), 3u);
  spit(d / "wrong.json", format_csl(s));
  auto wrong = read_sections((d / "wrong.json").string());
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.message().find("the content looks like .csl rather than .json"), std::string::npos) << wrong.message();
}

// === Files that cannot be read
TEST(FormatsIo, MissingDirectoryAndUnreadableFilesAreRefusedClearly) {
  const fs::path d = temp_dir();
  auto missing = read_sections((d / "nope.json").string());
  EXPECT_NE(missing.message().find("nope.json: no such file"), std::string::npos);
  fs::create_directories(d / "dir.json");
  auto dir = read_sections((d / "dir.json").string());
  EXPECT_NE(dir.message().find("is a directory"), std::string::npos);
  if (::geteuid() != 0) {  // root reads anything
    spit(d / "locked.json", "{}");
    fs::permissions(d / "locked.json", fs::perms::none);
    auto locked = read_sections((d / "locked.json").string());
    EXPECT_NE(locked.message().find("cannot be opened for reading"), std::string::npos) << locked.message();
  }
  EXPECT_FALSE(write_sections((d / "x.txt").string(), sample_set()));
  EXPECT_FALSE(write_sections((d / "no-such-dir" / "x.json").string(), sample_set()));
  EXPECT_FALSE(fs::exists(d / "no-such-dir"));
}

TEST(FormatsIo, CatalogueOfMalformedFilesGivesTheExpectedMessages) {
  const fs::path dir = fs::path(PLANESKETCH_SOURCE_DIR) / "tests/data/bad";
  std::ifstream manifest(dir / "expected.txt");
  ASSERT_TRUE(manifest) << "missing " << (dir / "expected.txt");
  std::map<std::string, std::string> expected;
  for (std::string line; std::getline(manifest, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto bar = line.find('|');
    ASSERT_NE(bar, std::string::npos) << line;
    expected[line.substr(0, bar)] = line.substr(bar + 1);
  }
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name == "expected.txt") continue;
    ++files;
    ASSERT_TRUE(expected.count(name)) << name << " is not listed in expected.txt";
    auto r = read_sections(entry.path().string());
    ASSERT_FALSE(r) << name << " was accepted";
    EXPECT_NE(r.message().find(entry.path().string()), std::string::npos) << r.message();
    EXPECT_NE(r.message().find(expected[name]), std::string::npos) << name << ": " << r.message();
    EXPECT_EQ(r.message().find('\n'), std::string::npos) << "one line: " << r.message();
  }
  EXPECT_EQ(files, static_cast<int>(expected.size()));
  EXPECT_GE(files, 50);
}

// === Real data
TEST(FormatsIo, EveryPublishedCslFileReads) {
  const fs::path root = fs::path(PLANESKETCH_SHARED_DIR) / "data/csl";
  if (!fs::exists(root)) GTEST_SKIP() << "no CSL data at " << root;
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".csl") continue;
    ++files;
    const std::string text = slurp(entry.path());
    std::istringstream head(text);
    std::string magic;
    long long planes = 0;
    head >> magic >> planes;
    std::vector<std::string> w;
    auto r = read_sections(entry.path().string(), &w);
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(static_cast<long long>(r->planes.size()), planes) << entry.path();
    EXPECT_GE(r->curves.size(), r->planes.size() / 2) << entry.path();
    const double diag = bounding_box(r->all_points()).diagonal();
    EXPECT_GT(diag, 0);
    for (const auto& c : r->curves) {
      EXPECT_GE(c.points.size(), 3u);
      for (const auto& q : c.points)
        EXPECT_LE(std::abs(r->planes[static_cast<std::size_t>(c.plane)].signed_distance(q)), 1e-12 * diag);
    }
    // And through the other two formats without loss.
    auto viajson = parse(format_contour_json(*r), ContourFormat::Json);
    ASSERT_TRUE(viajson) << viajson.message();
    auto viactr = parse(format_ctr2suf(*r), ContourFormat::Ctr2Suf);
    ASSERT_TRUE(viactr) << viactr.message();
    EXPECT_EQ(viactr->curves.size(), r->curves.size());
  }
  EXPECT_GE(files, 20);
}

// === The convert command
TEST(FormatsIo, ConvertCommandWritesOutputOrFailsWithOneLineAndNoFile) {
  const fs::path d = temp_dir();
  SectionSet s = sample_set();
  ASSERT_TRUE(write_sections((d / "in.json").string(), s));
  const std::string bin = PLANESKETCH_BINARY;
  const std::string ok_cmd = bin + " convert " + (d / "in.json").string() + " " + (d / "out.csl").string() + " 2>" + (d / "err.txt").string();
  ASSERT_EQ(std::system(ok_cmd.c_str()), 0) << slurp(d / "err.txt");
  auto back = read_sections((d / "out.csl").string());
  ASSERT_TRUE(back) << back.message();
  EXPECT_EQ(back->curves.size(), 3u);

  const fs::path bad = fs::path(PLANESKETCH_SOURCE_DIR) / "tests/data/bad/json_off_plane.json";
  const std::string bad_cmd = bin + " convert " + bad.string() + " " + (d / "bad.contour").string() + " 2>" + (d / "err.txt").string();
  EXPECT_NE(std::system(bad_cmd.c_str()), 0);
  const std::string err = slurp(d / "err.txt");
  EXPECT_NE(err.find("point 2 lies 0.5 off its plane"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(d / "bad.contour"));
  for (const auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().filename().string().rfind(".tmp-", 0), std::string::npos);
}
