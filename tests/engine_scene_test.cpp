// Scene logic without a device: camera conversion, ribbons, plane visuals, framing, mesh
// upload data, scene validation and PNG files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include <unistd.h>

#include "engine/frame_geometry.h"
#include "engine/image.h"
#include "engine/scene.h"

namespace ps::engine {
namespace {

// Pixel position of a clip-space vertex (Vulkan viewport transform).
Eigen::Vector2d to_pixel(const glm::vec4& c, const Camera& cam) {
  return {(double(c.x) / double(c.w) + 1.0) * 0.5 * cam.width,
          (double(c.y) / double(c.w) + 1.0) * 0.5 * cam.height};
}

Camera test_camera(bool ortho) {
  Camera cam;
  cam.eye = {2.0, 1.5, 3.0};
  cam.target = {0.1, -0.2, 0.05};
  cam.width = 320;
  cam.height = 200;
  cam.orthographic = ortho;
  cam.ortho_height = 3.0;
  cam.near_plane = 0.05;
  cam.far_plane = 50.0;
  return cam;
}

TEST(EngineCamera, VulkanClipLandsOnCameraProjectPixel) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (bool ortho : {false, true}) {
    const Camera cam = test_camera(ortho);
    const glm::mat4 m = vulkan_view_projection(cam);
    for (int i = 0; i < 200; ++i) {
      const Vec3 p(u(rng), u(rng), u(rng));
      const auto expected = cam.project(p);
      ASSERT_TRUE(expected.has_value());
      const glm::vec4 c = m * glm::vec4(float(p.x()), float(p.y()), float(p.z()), 1.f);
      const Eigen::Vector2d px = to_pixel(c, cam);
      EXPECT_NEAR(px.x(), expected->x(), 1e-3) << "ortho=" << ortho;
      EXPECT_NEAR(px.y(), expected->y(), 1e-3) << "ortho=" << ortho;
      // Depth: Vulkan [0, 1] is the OpenGL NDC depth mapped linearly.
      EXPECT_NEAR(double(c.z / c.w), 0.5 * (expected->z() + 1.0), 1e-5);
    }
  }
}

// === Ribbons

// The on-screen distance between the two sides of a ribbon at each point equals the width.
TEST(EngineRibbon, ScreenWidthFollowsPressure) {
  for (bool ortho : {false, true}) {
    const Camera cam = test_camera(ortho);
    // A straight world segment; sample points along it.
    std::vector<Vec3> pts;
    std::vector<float> pressure;
    for (int i = 0; i <= 10; ++i) {
      pts.push_back(Vec3(-0.5, 0.2, 0.0) + double(i) / 10.0 * Vec3(1.0, 0.1, -0.3));
      pressure.push_back(0.2f + 0.08f * float(i));
    }
    std::vector<ColorVertex> out;
    append_ribbon(cam, pts, pressure, 10.f, false, {0, 0, 0, 1}, 0.0, out);
    ASSERT_EQ(out.size(), 6u * 10u);
    for (std::size_t seg = 0; seg < 10; ++seg) {
      // Triangle order per segment: l0, r0, l1, l1, r0, r1.
      const auto l0 = to_pixel(out[6 * seg + 0].pos, cam), r0 = to_pixel(out[6 * seg + 1].pos, cam);
      const double width = (l0 - r0).norm();
      EXPECT_NEAR(width, 10.0 * pressure[seg], 1e-3) << "segment " << seg << " ortho=" << ortho;
      // The centre of the two sides is the projected point.
      const auto centre = cam.project(pts[seg]);
      EXPECT_NEAR(0.5 * (l0 + r0).x(), centre->x(), 1e-3);
      EXPECT_NEAR(0.5 * (l0 + r0).y(), centre->y(), 1e-3);
    }
  }
}

double total_screen_area(const std::vector<ColorVertex>& v, const Camera& cam) {
  double a = 0.0;
  for (std::size_t i = 0; i + 2 < v.size(); i += 3) {
    const auto p = to_pixel(v[i].pos, cam), q = to_pixel(v[i + 1].pos, cam),
               r = to_pixel(v[i + 2].pos, cam);
    a += 0.5 * std::abs((q - p).x() * (r - p).y() - (q - p).y() * (r - p).x());
  }
  return a;
}

TEST(EngineRibbon, ReversingTheStrokeKeepsItsArea) {
  const Camera cam = test_camera(false);
  std::vector<Vec3> pts;
  std::vector<float> pressure;
  for (int i = 0; i < 30; ++i) {
    const double t = 0.2 * i;
    pts.push_back(Vec3(std::cos(t), std::sin(t), 0.05 * t));
    pressure.push_back(0.5f + 0.5f * float(std::sin(t)));
  }
  std::vector<ColorVertex> a, b;
  append_ribbon(cam, pts, pressure, 6.f, false, {0, 0, 0, 1}, 0.0, a);
  std::reverse(pts.begin(), pts.end());
  std::reverse(pressure.begin(), pressure.end());
  append_ribbon(cam, pts, pressure, 6.f, false, {0, 0, 0, 1}, 0.0, b);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NEAR(total_screen_area(a, cam), total_screen_area(b, cam), 1e-6 * total_screen_area(a, cam));
}

TEST(EngineRibbon, ClosedLoopHasOneMoreSegment) {
  const Camera cam = test_camera(false);
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::vector<ColorVertex> open, closed;
  append_ribbon(cam, square, {}, 3.f, false, {0, 0, 0, 1}, 0.0, open);
  append_ribbon(cam, square, {}, 3.f, true, {0, 0, 0, 1}, 0.0, closed);
  EXPECT_EQ(open.size(), 6u * 3u);
  EXPECT_EQ(closed.size(), 6u * 4u);
}

TEST(EngineRibbon, PartsBehindTheEyeAreClippedAtTheNearPlane) {
  const Camera cam = test_camera(false);
  const Vec3 f = (cam.target - cam.eye).normalized();
  // From well in front of the camera to well behind it.
  const std::vector<Vec3> pts{cam.target, cam.eye - 2.0 * f + Vec3(0.1, 0.1, 0.0)};
  std::vector<ColorVertex> out;
  append_ribbon(cam, pts, {}, 4.f, false, {0, 0, 0, 1}, 0.0, out);
  ASSERT_EQ(out.size(), 6u);
  for (const auto& v : out) EXPECT_GE(double(v.pos.w), cam.near_plane * (1.0 - 1e-6));
  // Entirely behind: nothing.
  std::vector<ColorVertex> none;
  append_ribbon(cam, {cam.eye - f, cam.eye - 2.0 * f}, {}, 4.f, false, {0, 0, 0, 1}, 0.0, none);
  EXPECT_TRUE(none.empty());
}

TEST(EngineRibbon, DepthPullMovesTowardsTheCameraWithoutMovingPixels) {
  for (bool ortho : {false, true}) {
    const Camera cam = test_camera(ortho);
    const std::vector<Vec3> pts{{-0.3, 0.0, 0.2}, {0.4, 0.1, -0.1}};
    std::vector<ColorVertex> a, b;
    append_ribbon(cam, pts, {}, 4.f, false, {0, 0, 0, 1}, 0.0, a);
    append_ribbon(cam, pts, {}, 4.f, false, {0, 0, 0, 1}, 1e-2, b);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_LT(b[i].pos.z / b[i].pos.w, a[i].pos.z / a[i].pos.w);
      EXPECT_NEAR((to_pixel(a[i].pos, cam) - to_pixel(b[i].pos, cam)).norm(), 0.0, 1e-3);
    }
  }
}

// === Planes and framing

TEST(EnginePlanes, CornersLieOnThePlaneAroundTheProjectedCentre) {
  PlaneVisual p;
  p.plane.normal = Vec3(1.0, 2.0, -0.5).normalized();
  p.plane.offset = 0.7;
  p.center = Vec3(3.0, -1.0, 2.0);
  p.half_size = 1.5;
  const auto k = plane_corners(p);
  Vec3 sum = Vec3::Zero();
  for (const auto& c : k) {
    EXPECT_NEAR(p.plane.signed_distance(c), 0.0, 1e-12);
    sum += c;
  }
  EXPECT_LT((sum / 4.0 - p.plane.project(p.center)).norm(), 1e-12);
  EXPECT_NEAR((k[1] - k[0]).norm(), 3.0, 1e-12);
  EXPECT_NEAR((k[2] - k[1]).norm(), 3.0, 1e-12);
  // Counter-clockwise around the normal.
  EXPECT_GT((k[1] - k[0]).cross(k[2] - k[1]).dot(p.plane.normal), 0.0);
}

TEST(EnginePlanes, SelectionRaisesFillAndThickensBorder) {
  PlaneVisual p;
  PlaneVisual s = p;
  s.selected = true;
  EXPECT_GT(plane_fill_color(s).a, plane_fill_color(p).a);
  EXPECT_GT(plane_border_width_px(s), plane_border_width_px(p));
  EXPECT_EQ(plane_border_color(p).a, 1.f);
}

TEST(EngineLayout, BasicPlanesAreThreeAxisPlanesThroughTheBoxCentre) {
  Box3 box;
  box.extend({-1.0, 2.0, 0.0});
  box.extend({3.0, 4.0, 1.0});
  const auto planes = basic_planes(box);
  ASSERT_EQ(planes.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(planes[std::size_t(k)].plane.axis(), k);
    EXPECT_NEAR(planes[std::size_t(k)].plane.offset, box.center()[k], 1e-12);
    EXPECT_GE(planes[std::size_t(k)].half_size, 0.5 * box.size().maxCoeff());
  }
}

// Every plane corner lands inside the image, for every view and aspect; the framing is
// invariant under translating and scaling the content.
TEST(EngineLayout, FramingKeepsThePlanesInsideTheImage) {
  for (View view : {View::iso, View::x, View::y, View::z})
    for (auto [w, h] : {std::pair{320, 200}, std::pair{200, 320}, std::pair{256, 256}}) {
      Box3 box;
      box.extend({-0.5, -1.0, -0.2});
      box.extend({0.7, 0.8, 1.4});
      const Camera cam = framing_camera(box, view, w, h);
      std::vector<Eigen::Vector2d> pixels;
      for (const auto& p : basic_planes(box))
        for (const auto& c : plane_corners(p)) {
          const auto px = cam.project(c);
          ASSERT_TRUE(px.has_value());
          EXPECT_GE(px->x(), 0.0);
          EXPECT_LE(px->x(), double(w));
          EXPECT_GE(px->y(), 0.0);
          EXPECT_LE(px->y(), double(h));
          EXPECT_GT(px->z(), -1.0);
          EXPECT_LT(px->z(), 1.0);
          pixels.push_back(px->head<2>());
        }
      // Moved and scaled content frames to the same pixels.
      Box3 moved;
      moved.extend(box.min * 1000.0 + Vec3(5e3, -2e3, 7e3));
      moved.extend(box.max * 1000.0 + Vec3(5e3, -2e3, 7e3));
      const Camera cam2 = framing_camera(moved, view, w, h);
      std::size_t i = 0;
      for (const auto& p : basic_planes(moved))
        for (const auto& c : plane_corners(p)) {
          const auto px = cam2.project(c);
          ASSERT_TRUE(px.has_value());
          EXPECT_NEAR(px->x(), pixels[i].x(), 1e-6 * w);
          EXPECT_NEAR(px->y(), pixels[i].y(), 1e-6 * h);
          ++i;
        }
    }
}

TEST(EngineLayout, ParseView) {
  EXPECT_EQ(parse_view("iso"), View::iso);
  EXPECT_EQ(parse_view("y"), View::y);
  EXPECT_FALSE(parse_view("top").has_value());
}

// === Mesh upload data

TriMesh octahedron() {
  TriMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

TEST(EngineMesh, VertexNormalsOfAnOctahedronPointOutwards) {
  const TriMesh m = octahedron();
  const auto n = vertex_normals(m);
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    EXPECT_LT((n[i] - m.vertices[i]).norm(), 1e-12) << "vertex " << i;
}

TEST(EngineMesh, IndexedAndExpandedUploadsDescribeTheSameTriangles) {
  const TriMesh m = octahedron();
  const MeshBuffers indexed = prepare_mesh(m, false);
  const MeshBuffers expanded = prepare_mesh(m, true);
  EXPECT_EQ(indexed.vertices.size(), m.vertices.size());
  EXPECT_EQ(expanded.vertices.size(), 3 * m.faces.size());
  ASSERT_EQ(indexed.indices.size(), expanded.indices.size());
  for (std::size_t i = 0; i < indexed.indices.size(); ++i) {
    EXPECT_EQ(expanded.indices[i], i);  // corner k of face f is vertex 3f + k
    const auto& a = indexed.vertices[indexed.indices[i]];
    const auto& b = expanded.vertices[expanded.indices[i]];
    EXPECT_EQ(a.pos, b.pos);
    EXPECT_EQ(a.normal, b.normal);
  }
}

TEST(EngineMesh, ClosedOutwardDetection) {
  TriMesh m = octahedron();
  EXPECT_TRUE(is_closed_and_outward(m));
  TriMesh inward = m;
  for (auto& f : inward.faces) std::swap(f[1], f[2]);
  EXPECT_FALSE(is_closed_and_outward(inward));  // negative volume
  TriMesh open = m;
  open.faces.pop_back();
  EXPECT_FALSE(is_closed_and_outward(open));
  TriMesh flipped_one = m;
  std::swap(flipped_one.faces[3][1], flipped_one.faces[3][2]);
  EXPECT_FALSE(is_closed_and_outward(flipped_one));  // inconsistent orientation
  // Translation does not change the answer (signed volume is translation invariant).
  TriMesh moved = m;
  for (auto& v : moved.vertices) v += Vec3(100.0, -50.0, 20.0);
  EXPECT_TRUE(is_closed_and_outward(moved));
}

TEST(EngineMesh, FingerprintChangesWithContent) {
  TriMesh m = octahedron();
  const uint64_t a = mesh_fingerprint(m);
  EXPECT_EQ(a, mesh_fingerprint(octahedron()));
  m.vertices[3].y() = std::nextafter(m.vertices[3].y(), 0.0);
  EXPECT_NE(a, mesh_fingerprint(m));
  TriMesh f = octahedron();
  std::swap(f.faces[0][0], f.faces[0][1]);
  EXPECT_NE(a, mesh_fingerprint(f));
}

// === Scene validation

TEST(EngineScene, ValidationNamesTheBadField) {
  Scene s;
  s.camera.width = 64;
  s.camera.height = 64;
  EXPECT_TRUE(validate_scene(s).is_ok());

  Scene bad_size = s;
  bad_size.camera.width = 0;
  EXPECT_NE(validate_scene(bad_size).message().find("scene.camera"), std::string::npos);

  Scene bad_pressure = s;
  bad_pressure.strokes.push_back({{Vec3::Zero(), Vec3::UnitX()}, {1.f}, {}, 4.f, false});
  EXPECT_NE(validate_scene(bad_pressure).message().find("scene.strokes[0]"), std::string::npos);

  Scene bad_face = s;
  bad_face.solid = MeshVisual{octahedron(), {}, false};
  bad_face.solid->mesh.faces[2][1] = 6;
  const std::string msg = validate_scene(bad_face).message();
  EXPECT_NE(msg.find("scene.solid: face 2"), std::string::npos) << msg;

  Scene bad_plane = s;
  PlaneVisual p;
  p.plane.normal = Vec3(1.0, 1.0, 0.0);  // not unit length
  bad_plane.planes.push_back(p);
  EXPECT_NE(validate_scene(bad_plane).message().find("scene.planes[0]"), std::string::npos);
}

TEST(EngineScene, FrameGeometrySortsStrokesByOpacity) {
  Scene s;
  s.camera = test_camera(false);
  s.planes = basic_planes(bounding_box(octahedron().vertices));
  s.strokes.push_back({{Vec3::Zero(), Vec3::UnitX()}, {}, {0, 0, 0, 1.f}, 4.f, false});
  s.strokes.push_back({{Vec3::Zero(), Vec3::UnitY()}, {}, {0, 0, 0, 0.5f}, 4.f, false});
  const FrameGeometry fg = build_frame_geometry(s);
  EXPECT_EQ(fg.plane_fills.size(), 3u * 6u);
  // 3 closed borders (4 segments) + the opaque stroke; the translucent stroke alone.
  EXPECT_EQ(fg.opaque_ribbons.size(), 6u * (3u * 4u + 1u));
  EXPECT_EQ(fg.translucent_ribbons.size(), 6u);
}

TEST(EngineScene, TranslucentBoundsCoverTheFillsAndGrowToTheImageBehindTheEye) {
  Scene s;
  s.camera = test_camera(false);
  PlaneVisual p;
  p.plane.normal = Vec3::UnitY();
  p.center = Vec3(0.0, 0.0, 0.0);
  p.half_size = 0.3;
  s.planes.push_back(p);
  const FrameGeometry fg = build_frame_geometry(s);
  const PixelBounds& b = fg.translucent_bounds;
  ASSERT_FALSE(b.empty());
  EXPECT_LT((b.x1 - b.x0) * (b.y1 - b.y0), s.camera.width * s.camera.height / 2);
  for (const auto& c : plane_corners(p)) {
    const auto px = s.camera.project(c);
    EXPECT_GE(px->x(), b.x0);
    EXPECT_LE(px->x(), b.x1);
    EXPECT_GE(px->y(), b.y0);
    EXPECT_LE(px->y(), b.y1);
  }
  // A plane through the eye: its projection is unbounded, so the whole image.
  s.planes[0].center = s.camera.eye;
  s.planes[0].half_size = 10.0;
  const PixelBounds all = build_frame_geometry(s).translucent_bounds;
  EXPECT_EQ(all.x0, 0);
  EXPECT_EQ(all.y0, 0);
  EXPECT_EQ(all.x1, s.camera.width);
  EXPECT_EQ(all.y1, s.camera.height);
  // Nothing translucent: empty.
  s.planes.clear();
  EXPECT_TRUE(build_frame_geometry(s).translucent_bounds.empty());
}

// === Images and PNG files

TEST(EngineImage, PngRoundTripAndAtomicFailure) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("ps_engine_png_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Image img{7, 5, {}};
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x)
      for (int c = 0; c < 4; ++c) img.rgba.push_back(uint8_t(x * 30 + y * 7 + c * 50));
  const std::string path = (dir / "a.png").string();
  ASSERT_TRUE(write_png(path, img).is_ok());
  auto back = read_png(path);
  ASSERT_TRUE(back.is_ok()) << back.message();
  EXPECT_EQ(back->width, 7);
  EXPECT_EQ(back->height, 5);
  EXPECT_EQ(back->rgba, img.rgba);
  const ImageDiff same = compare_images(img, *back);
  EXPECT_TRUE(same.same_size);
  EXPECT_EQ(same.max_channel_diff, 0);

  // Only the expected files exist (no temporary left behind).
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);

  const std::string missing = (dir / "no_such_dir" / "b.png").string();
  const Status st = write_png(missing, img);
  EXPECT_FALSE(st.is_ok());
  EXPECT_NE(st.message().find("does not exist"), std::string::npos) << st.message();
  EXPECT_FALSE(fs::exists(missing));

  Image broken = img;
  broken.rgba.pop_back();
  EXPECT_FALSE(write_png((dir / "c.png").string(), broken).is_ok());
  EXPECT_FALSE(fs::exists(dir / "c.png"));

  Image other = img;
  other.rgba[4 * 3 + 1] = uint8_t(other.rgba[4 * 3 + 1] + 9);
  const ImageDiff d = compare_images(img, other, 2);
  EXPECT_EQ(d.max_channel_diff, 9);
  EXPECT_EQ(d.differing_pixels, 1u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ps::engine
