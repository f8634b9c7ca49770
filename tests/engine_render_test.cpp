// Headless rendering on the Vulkan device (lavapipe here), validation layers on.
//
// Golden images live in tests/goldens/*.png. Update them with scripts/update-goldens (sets
// PLANESKETCH_UPDATE_GOLDENS=1 and runs the engine tests). A failing comparison writes the
// actual image and an amplified difference image next to the build's test binary
// (<name>.actual.png, <name>.diff.png) so the failure can be looked at.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "engine/image.h"
#include "engine/renderer.h"
#include "engine/scene.h"
#include "modeling/mesh_io.h"
#include "tests/golden_compare.h"
#include "tests/mesh_fixtures.h"

namespace ps::engine {
namespace {

namespace fs = std::filesystem;

// === Test content (procedural, so the goldens depend on no data files)

using ps::testing::torus;
using ps::testing::uv_sphere;

constexpr int kW = 256, kH = 160;

Scene base_scene() {
  Box3 box;
  box.extend(Vec3(-1, -1, -1));
  box.extend(Vec3(1, 1, 1));
  Scene s;
  s.camera = framing_camera(box, View::iso, kW, kH);
  s.background = {0.97f, 0.97f, 0.95f, 1.f};
  s.planes = basic_planes(box);
  return s;
}

StrokeVisual spiral_stroke(double z, Rgba color, bool closed) {
  StrokeVisual st;
  for (int i = 0; i <= 40; ++i) {
    const double t = 2 * M_PI * i / 40.0;
    const double r = closed ? 0.7 : 0.2 + 0.6 * i / 40.0;
    st.points.push_back(Vec3(r * std::cos(t), r * std::sin(t), z));
    st.pressure.push_back(float(0.3 + 0.7 * std::abs(std::sin(1.5 * t))));
  }
  if (closed) st.points.pop_back(), st.pressure.pop_back();
  st.color = color;
  st.width_px = 5.f;
  st.closed = closed;
  return st;
}

// === One renderer for the whole binary (creating a device is the slow part).

class EngineRender : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    RendererOptions o;
    o.width = kW;
    o.height = kH;
    o.validation = true;
    o.prefer_gpu = false;  // goldens are lavapipe's output
    auto r = create_offscreen_renderer(o);
    if (!r) {
      creation_error_ = new std::string(r.message());
      return;
    }
    renderer_ = r->release();
  }
  static void TearDownTestSuite() {
    delete renderer_;
    renderer_ = nullptr;
    delete creation_error_;
    creation_error_ = nullptr;
  }
  void SetUp() override {
    ASSERT_NE(renderer_, nullptr) << "no renderer: " << *creation_error_;
  }
  void TearDown() override {
    if (renderer_) {
      EXPECT_EQ(renderer_->validation_messages(), 0u) << "validation reported problems";
    }
  }
  Image render(const Scene& s) {
    auto img = renderer_->render(s);
    EXPECT_TRUE(img.is_ok()) << img.message();
    return img.is_ok() ? std::move(*img) : Image{};
  }

  static Renderer* renderer_;
  static std::string* creation_error_;
};
Renderer* EngineRender::renderer_ = nullptr;
std::string* EngineRender::creation_error_ = nullptr;

bool pixel_near(const Image& img, int x, int y, Rgba c, int tol) {
  const uint8_t* p = img.pixel(x, y);
  const auto ch = [](float v) { return int(std::lround(v * 255.f)); };
  return std::abs(p[0] - ch(c.r)) <= tol && std::abs(p[1] - ch(c.g)) <= tol &&
         std::abs(p[2] - ch(c.b)) <= tol;
}

// === Goldens

TEST_F(EngineRender, PlanesAndStrokesGolden) {
  Scene s = base_scene();
  s.planes[2].selected = true;
  s.strokes.push_back(spiral_stroke(0.0, {0.1f, 0.1f, 0.15f, 1.f}, false));
  s.strokes.push_back(spiral_stroke(0.0, {0.8f, 0.3f, 0.0f, 0.6f}, true));  // translucent
  const Image img = render(s);
  EXPECT_IMAGE_MATCHES_GOLDEN(img, "planes_strokes");
}

TEST_F(EngineRender, SolidWireframeGolden) {
  Scene s = base_scene();
  s.solid = MeshVisual{torus(Vec3::Zero(), 0.65, 0.25, 32, 16), {0.75f, 0.7f, 0.6f, 1.f}, true};
  const Image img = render(s);
  EXPECT_IMAGE_MATCHES_GOLDEN(img, "solid_wireframe");
}

TEST_F(EngineRender, TranslucentPreviewOverSolidGolden) {
  Scene s = base_scene();
  s.solid = MeshVisual{uv_sphere(Vec3::Zero(), 0.35, 16, 24), {0.9f, 0.5f, 0.2f, 1.f}, false};
  s.preview = MeshVisual{torus(Vec3::Zero(), 0.6, 0.3, 32, 16), {0.3f, 0.5f, 0.9f, 0.45f}, false};
  s.strokes.push_back(spiral_stroke(0.0, {0.f, 0.f, 0.f, 1.f}, true));
  const Image img = render(s);
  EXPECT_IMAGE_MATCHES_GOLDEN(img, "preview_over_solid");
}

TEST_F(EngineRender, ElephantDefaultSceneGolden) {
  const std::string path = std::string(PLANESKETCH_CGAL_DATA) + "/elephant.off";
  if (!fs::exists(path)) GTEST_SKIP() << "CGAL data mesh " << path << " is absent";
  auto mesh = read_mesh(path);
  ASSERT_TRUE(mesh.is_ok()) << mesh.message();
  const Image img = render(default_scene(*mesh, View::iso, kW, kH));
  EXPECT_IMAGE_MATCHES_GOLDEN(img, "elephant_iso");
}

// === Invariants

// Weighted blended OIT: the image does not depend on the order of translucent objects.
TEST_F(EngineRender, TranslucentDrawOrderDoesNotMatter) {
  Scene a = base_scene();
  a.strokes.push_back(spiral_stroke(0.2, {0.9f, 0.1f, 0.1f, 0.5f}, true));
  a.strokes.push_back(spiral_stroke(-0.2, {0.1f, 0.1f, 0.9f, 0.5f}, false));
  Scene b = a;
  std::reverse(b.planes.begin(), b.planes.end());
  std::reverse(b.strokes.begin(), b.strokes.end());
  const Image ia = render(a), ib = render(b);
  const ImageDiff d = compare_images(ia, ib, 1);
  EXPECT_TRUE(d.same_size);
  EXPECT_EQ(d.differing_pixels, 0u) << "largest channel difference " << d.max_channel_diff;
  EXPECT_LE(d.max_channel_diff, 1);
  // The content is really translucent and overlapping: not just background.
  const ImageDiff vs_empty = compare_images(ia, render(Scene{a.camera, a.background, {}, {}, {}, {}}));
  EXPECT_GT(vs_empty.differing_fraction, 0.3);
}

// A world point lands on the pixel Camera::project gives (checks the y flip on the device).
TEST_F(EngineRender, StrokeLandsOnProjectedPixel) {
  Scene s = base_scene();
  s.planes.clear();
  const Rgba ink{0.9f, 0.1f, 0.6f, 1.f};
  for (const Vec3& p : {Vec3(0.6, 0.5, -0.3), Vec3(-0.7, -0.4, 0.2), Vec3(0.1, 0.8, 0.7)}) {
    Scene t = s;
    // A short, thick stroke through p along x.
    t.strokes.push_back({{p - Vec3(0.02, 0, 0), p + Vec3(0.02, 0, 0)}, {}, ink, 8.f, false});
    const Image img = render(t);
    const auto px = s.camera.project(p);
    ASSERT_TRUE(px.has_value());
    const int x = int(std::floor(px->x())), y = int(std::floor(px->y()));
    EXPECT_TRUE(pixel_near(img, x, y, ink, 1)) << "at " << x << "," << y;
    // The pixel mirrored vertically is background (a missing y flip would hit it).
    EXPECT_TRUE(pixel_near(img, x, kH - 1 - y, s.background, 1));
  }
}

// An opaque solid hides translucent planes behind it and is tinted by planes in front.
TEST_F(EngineRender, OpaqueDepthOccludesTranslucency) {
  Scene s = base_scene();
  s.planes.resize(1);  // the x = 0 plane only
  s.solid = MeshVisual{uv_sphere(Vec3(0.5, 0, 0), 0.3, 16, 24), {0.2f, 0.8f, 0.2f, 1.f}, false};
  Scene no_plane = s;
  no_plane.planes.clear();
  const Image with = render(s), without = render(no_plane);
  // Sphere centre is in front of the plane (x > 0 is the camera side): identical pixels.
  const auto c = s.camera.project(Vec3(0.5, 0, 0));
  const int x = int(c->x()), y = int(c->y());
  for (int k = 0; k < 4; ++k) EXPECT_EQ(with.pixel(x, y)[k], without.pixel(x, y)[k]);
  // Behind the plane the sphere is tinted.
  Scene behind = s;
  behind.solid->mesh = uv_sphere(Vec3(-0.5, 0, 0), 0.3, 16, 24);
  Scene behind_no_plane = behind;
  behind_no_plane.planes.clear();
  const auto cb = s.camera.project(Vec3(-0.5, 0, 0));
  const Image b1 = render(behind), b2 = render(behind_no_plane);
  const uint8_t* p1 = b1.pixel(int(cb->x()), int(cb->y()));
  const uint8_t* p2 = b2.pixel(int(cb->x()), int(cb->y()));
  EXPECT_GT(std::abs(int(p1[0]) - int(p2[0])) + std::abs(int(p1[1]) - int(p2[1])), 10);
}

// Reusing the renderer: same scene -> same bytes; unchanged meshes are not uploaded again.
TEST_F(EngineRender, ReuseIsDeterministicAndCachesMeshes) {
  Scene s = base_scene();
  s.solid = MeshVisual{uv_sphere(Vec3::Zero(), 0.4, 12, 16), {0.7f, 0.7f, 0.7f, 1.f}, false};
  const Image a = render(s);
  const std::size_t uploads = renderer_->stats().mesh_uploads;
  const Image b = render(s);
  EXPECT_EQ(a.rgba, b.rgba);
  EXPECT_EQ(renderer_->stats().mesh_uploads, uploads);
  s.camera.eye *= 1.1;  // camera moves: no upload
  render(s);
  EXPECT_EQ(renderer_->stats().mesh_uploads, uploads);
  s.solid->mesh.vertices[0].y() += 0.1;  // mesh changes: one upload
  render(s);
  EXPECT_EQ(renderer_->stats().mesh_uploads, uploads + 1);
  s.solid->wireframe = true;  // different layout: one upload
  render(s);
  EXPECT_EQ(renderer_->stats().mesh_uploads, uploads + 2);
}

// Culling back faces of a closed, outward-oriented opaque mesh does not change the image (a
// wrong winding convention would show the inside); an open mesh is never culled.
TEST_F(EngineRender, BackFaceCullingOfClosedSolidsIsInvisible) {
  RendererOptions o;
  o.width = kW;
  o.height = kH;
  o.validation = true;
  o.prefer_gpu = false;
  o.cull_closed_solids = false;
  auto unculled = create_offscreen_renderer(o);
  ASSERT_TRUE(unculled.is_ok()) << unculled.message();
  Scene s = base_scene();
  s.solid = MeshVisual{torus(Vec3::Zero(), 0.6, 0.3, 40, 20), {0.6f, 0.7f, 0.8f, 1.f}, false};
  auto a = renderer_->render(s), b = (*unculled)->render(s);
  ASSERT_TRUE(a.is_ok() && b.is_ok());
  EXPECT_EQ(compare_images(*a, *b).max_channel_diff, 0);
  // Inside out (closed, consistently oriented, negative volume) or open: not culled, so the
  // image is again the same as without culling.
  for (auto& f : s.solid->mesh.faces) std::swap(f[1], f[2]);
  auto c = renderer_->render(s), d = (*unculled)->render(s);
  ASSERT_TRUE(c.is_ok() && d.is_ok());
  EXPECT_EQ(compare_images(*c, *d).max_channel_diff, 0);
  s.solid->mesh.faces.resize(s.solid->mesh.faces.size() / 2);
  auto e = renderer_->render(s), f = (*unculled)->render(s);
  ASSERT_TRUE(e.is_ok() && f.is_ok());
  EXPECT_EQ(compare_images(*e, *f).max_channel_diff, 0);
  EXPECT_EQ((*unculled)->validation_messages(), 0u);
}

// Targets follow the camera's size.
TEST_F(EngineRender, TargetsFollowCameraSize) {
  Scene s = base_scene();
  s.camera = framing_camera(bounding_box({Vec3(-1, -1, -1), Vec3(1, 1, 1)}), View::z, 97, 61);
  const Image img = render(s);
  EXPECT_EQ(img.width, 97);
  EXPECT_EQ(img.height, 61);
  EXPECT_EQ(img.rgba.size(), 97u * 61u * 4u);
  const Image back = render(base_scene());
  EXPECT_EQ(back.width, kW);
}

// A bad scene is refused with the field named; the renderer stays usable.
TEST_F(EngineRender, BadSceneIsRefusedAndRendererRecovers) {
  Scene s = base_scene();
  s.solid = MeshVisual{uv_sphere(Vec3::Zero(), 0.4, 8, 8), {}, false};
  s.solid->mesh.faces[5][2] = 100000;
  auto r = renderer_->render(s);
  ASSERT_FALSE(r.is_ok());
  EXPECT_NE(r.message().find("scene.solid: face 5"), std::string::npos) << r.message();
  EXPECT_FALSE(renderer_->read_back().is_ok());  // nothing drawn since the failure
  const Image ok = render(base_scene());
  EXPECT_EQ(ok.width, kW);
}

}  // namespace
}  // namespace ps::engine
