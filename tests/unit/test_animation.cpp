// glTF node animations: a generated .gltf with one channel per interpolation and path, checked
// against hand-computed values; malformed animations refused; Debian's animated test models
// evaluated without NaN.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/log.h"
#include "gltf_test_util.h"
#include "scene/animation.h"
#include "scene/loader.h"
#include "scene/merge.h"
#include "scene/skinning.h"

using namespace rayster;
using namespace rayster::test;
namespace fs = std::filesystem;

namespace {

constexpr float kEps = 1e-5f;
const float kHalfSqrt2 = std::sqrt(0.5f);  // sin 45° = cos 45°

// A unit box centred on the origin (8 shared corners, normals along the diagonals), mesh 0.
void addBoxMesh(Doc& d) {
  std::vector<float> pos, nrm;
  for (int i = 0; i < 8; ++i) {
    const float x = i & 1 ? 0.5f : -0.5f, y = i & 2 ? 0.5f : -0.5f, z = i & 4 ? 0.5f : -0.5f;
    pos.insert(pos.end(), {x, y, z});
    nrm.insert(nrm.end(), {x * 2 / std::sqrt(3.0f), y * 2 / std::sqrt(3.0f), z * 2 / std::sqrt(3.0f)});
  }
  const std::vector<uint16_t> idx = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                     2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  const int p = d.floats(pos, "VEC3", 3), n = d.floats(nrm, "VEC3", 3);
  const int i = d.accessor(d.view(idx), kUShort, idx.size(), "SCALAR");
  d.j["meshes"] = Json::array(
      {{{"name", "box"},
        {"primitives", Json::array({{{"attributes", {{"POSITION", p}, {"NORMAL", n}}}, {"indices", i}}})}}});
}

// Adds a sampler and a channel to animation `animation` (created when missing).
void addChannel(Doc& d, int node, const char* path, const char* interp, const std::vector<float>& times,
                const std::vector<float>& values, int animation = 0) {
  const int components = std::string(path) == "rotation" ? 4 : 3;
  Json& anim = d.j["animations"][size_t(animation)];
  if (!anim.contains("name")) anim["name"] = fmt::format("anim{}", animation);
  const int input = d.floats(times, "SCALAR", 1);
  const int output = d.floats(values, components == 4 ? "VEC4" : "VEC3", components);
  anim["samplers"].push_back({{"input", input}, {"output", output}, {"interpolation", interp}});
  anim["channels"].push_back(
      {{"sampler", int(anim["samplers"].size()) - 1}, {"target", {{"node", node}, {"path", path}}}});
}

enum Node { kTranslated, kRotated, kStepped, kSpline, kParent, kChild, kStatic };

// The test asset: every node but the parent holds the box; one animation of length 2 s.
//  translated: translation LINEAR (0,0,0) at 0 s -> (4,2,0) at 2 s; rest pose (9,9,9)
//  rotated:    rotation LINEAR identity at 0 s -> 90° about +Y at 1 s
//  stepped:    scale STEP 1 at 0 s, 2 at 1 s, 3 at 2 s
//  spline:     translation CUBICSPLINE (0,0,0) out-tangent (1,0,0) at 0 s ->
//              (4,0,0) in-tangent (0,3,0) at 2 s
//  parent:     translation LINEAR (0,0,0) -> (0,10,0) over 2 s, no mesh; child at local (1,0,0)
//  static:     not animated, at (0,0,-5)
Doc animatedDoc() {
  Doc d;
  addBoxMesh(d);
  d.j["nodes"] = Json::array({
      {{"name", "translated"}, {"mesh", 0}, {"translation", {9, 9, 9}}},
      {{"name", "rotated"}, {"mesh", 0}},
      {{"name", "stepped"}, {"mesh", 0}},
      {{"name", "spline"}, {"mesh", 0}},
      {{"name", "parent"}, {"children", {int(kChild)}}},
      {{"name", "child"}, {"mesh", 0}, {"translation", {1, 0, 0}}},
      {{"name", "static"}, {"mesh", 0}, {"translation", {0, 0, -5}}},
  });
  d.j["scenes"] = Json::array({{{"nodes", {kTranslated, kRotated, kStepped, kSpline, kParent, kStatic}}}});
  d.j["scene"] = 0;
  addChannel(d, kTranslated, "translation", "LINEAR", {0, 2}, {0, 0, 0, 4, 2, 0});
  addChannel(d, kRotated, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, kHalfSqrt2, 0, kHalfSqrt2});
  addChannel(d, kStepped, "scale", "STEP", {0, 1, 2}, {1, 1, 1, 2, 2, 2, 3, 3, 3});
  addChannel(d, kSpline, "translation", "CUBICSPLINE", {0, 2},
             {/*in*/ 0, 0, 0, /*value*/ 0, 0, 0, /*out*/ 1, 0, 0, /*in*/ 0, 3, 0, /*value*/ 4, 0, 0, /*out*/ 0, 0, 0});
  addChannel(d, kParent, "translation", "LINEAR", {0, 2}, {0, 0, 0, 0, 10, 0});
  return d;
}

scene::Scene loadAnimated() {
  TempDir dir;
  Result<scene::Scene> scene = loadBytes(dir, animatedDoc().gltf(), "animated.gltf");
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(*scene) : scene::Scene{};
}

const scene::Instance& instance(const scene::Scene& scene, const std::string& name) {
  auto it = std::find_if(scene.instances.begin(), scene.instances.end(),
                         [&](const scene::Instance& i) { return i.name == name; });
  RAYSTER_ASSERT(it != scene.instances.end(), "no such instance in the test scene");
  return *it;
}

glm::vec3 position(const scene::Scene& scene, const std::string& name) {
  return glm::vec3(instance(scene, name).worldFromObject[3]);
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float eps = kEps) {
  EXPECT_NEAR(actual.x, expected.x, eps);
  EXPECT_NEAR(actual.y, expected.y, eps);
  EXPECT_NEAR(actual.z, expected.z, eps);
}

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

void expectRefused(const Result<scene::Scene>& result, const std::string& substring) {
  ASSERT_FALSE(result.ok()) << "expected a refusal mentioning: " << substring;
  EXPECT_EQ(result.error().code, ExitCode::BadInput);
  EXPECT_NE(result.error().message.find(substring), std::string::npos) << result.error().message;
  EXPECT_EQ(result.error().message.find('\n'), std::string::npos) << result.error().message;
}

TEST(Animation, LoadsModelAndRestPose) {
  scene::Scene scene = loadAnimated();
  ASSERT_TRUE(scene.animated());
  ASSERT_EQ(scene.animations.size(), 1u);
  EXPECT_EQ(scene.animations[0].name, "anim0");
  EXPECT_FLOAT_EQ(scene.animations[0].duration, 2.0f);
  EXPECT_EQ(scene.animations[0].channels.size(), 5u);
  EXPECT_EQ(scene.nodes.size(), 7u);
  for (size_t i = 0; i < scene.nodes.size(); ++i) EXPECT_LT(scene.nodes[i].parent, int32_t(i));
  // Loading does not play the animation: the instances sit in the glTF rest pose.
  expectNear(position(scene, "translated"), {9, 9, 9});
  expectNear(position(scene, "child"), {1, 0, 0});
  EXPECT_GE(instance(scene, "child").node, 0);
  EXPECT_EQ(instance(scene, "static").node, -1);
  const scene::Scene stillLife = [] {
    TempDir dir;
    Result<scene::Scene> s = loadBytes(dir, quadDoc().gltf());
    EXPECT_TRUE(s.ok());
    return s.ok() ? std::move(*s) : scene::Scene{};
  }();
  EXPECT_FALSE(stillLife.animated());
  ASSERT_EQ(stillLife.instances.size(), 1u);
  EXPECT_EQ(stillLife.instances[0].node, -1);
}

TEST(Animation, TranslationLinearHalfway) {
  scene::Scene scene = loadAnimated();
  EXPECT_TRUE(scene::evaluateAnimations(scene, 1.0f));
  expectNear(position(scene, "translated"), {2, 1, 0});
  scene::evaluateAnimations(scene, 0.5f);
  expectNear(position(scene, "translated"), {1, 0.5f, 0});
}

TEST(Animation, RotationSlerpHalfwayIs45DegreesAboutY) {
  scene::Scene scene = loadAnimated();
  scene::evaluateAnimations(scene, 0.5f);
  const glm::mat4& m = instance(scene, "rotated").worldFromObject;
  // +45° about +Y takes +X to (cos 45°, 0, -sin 45°) and leaves +Y alone.
  expectNear(glm::vec3(m * glm::vec4(1, 0, 0, 0)), {kHalfSqrt2, 0, -kHalfSqrt2});
  expectNear(glm::vec3(m * glm::vec4(0, 1, 0, 0)), {0, 1, 0});
  const glm::quat q = scene.nodes[size_t(instance(scene, "rotated").node)].rotation;
  EXPECT_NEAR(glm::length(q), 1.0f, kEps);
  EXPECT_NEAR(glm::degrees(glm::angle(q)), 45.0f, 1e-3f);
}

TEST(Animation, SlerpTakesTheShortestPath) {
  // q and -q are the same rotation: halfway from identity to -(90° about Y) is still +45°.
  const glm::quat a(1, 0, 0, 0), b(-kHalfSqrt2, 0, -kHalfSqrt2, 0);
  const glm::quat half = scene::slerpShortest(a, b, 0.5f);
  const glm::vec3 x = half * glm::vec3(1, 0, 0);
  expectNear(x, {kHalfSqrt2, 0, -kHalfSqrt2});
}

TEST(Animation, StepHoldsThePreviousKey) {
  scene::Scene scene = loadAnimated();
  for (float t : {1.0f, 1.5f, 1.999f}) {
    scene::evaluateAnimations(scene, t);
    const glm::mat4& m = instance(scene, "stepped").worldFromObject;
    EXPECT_NEAR(glm::length(glm::vec3(m[0])), 2.0f, kEps) << "t = " << t;
    EXPECT_NEAR(glm::length(glm::vec3(m[1])), 2.0f, kEps) << "t = " << t;
  }
  scene::evaluateAnimations(scene, 0.99f);
  EXPECT_NEAR(glm::length(glm::vec3(instance(scene, "stepped").worldFromObject[0])), 1.0f, kEps);
  scene::evaluateAnimations(scene, 2.0f);
  EXPECT_NEAR(glm::length(glm::vec3(instance(scene, "stepped").worldFromObject[0])), 3.0f, kEps);
}

TEST(Animation, CubicSplineHitsKeysAndFollowsHermite) {
  scene::Scene scene = loadAnimated();
  scene::evaluateAnimations(scene, 0.0f);
  expectNear(position(scene, "spline"), {0, 0, 0});
  scene::evaluateAnimations(scene, 2.0f);
  expectNear(position(scene, "spline"), {4, 0, 0});
  // s = 0.5, dt = 2: p = h00 p0 + h10 dt m0 + h01 p1 + h11 dt m1
  //                    = 0.5 (0,0,0) + 0.125 * 2 (1,0,0) + 0.5 (4,0,0) - 0.125 * 2 (0,3,0) = (2.25, -0.75, 0)
  scene::evaluateAnimations(scene, 1.0f);
  expectNear(position(scene, "spline"), {2.25f, -0.75f, 0});
  // s = 0.25: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875
  scene::evaluateAnimations(scene, 0.5f);
  expectNear(position(scene, "spline"), {0.140625f * 2 + 0.15625f * 4, -0.046875f * 2 * 3, 0});
}

TEST(Animation, CubicSplineRotationIsNormalised) {
  scene::AnimationChannel channel;
  channel.path = scene::AnimationChannel::Rotation;
  channel.interp = scene::AnimationChannel::CubicSpline;
  channel.times = {0, 1};
  // Zero tangents between identity and 90° about Y: the raw Hermite blend is shorter than unit.
  channel.values = {
      glm::vec4(0), glm::vec4(0, 0, 0, 1), glm::vec4(0), glm::vec4(0), glm::vec4(0, kHalfSqrt2, 0, kHalfSqrt2),
      glm::vec4(0)};
  const glm::vec4 q = scene::sampleChannel(channel, 0.5f);
  EXPECT_NEAR(glm::length(q), 1.0f, kEps);
  EXPECT_NEAR(q.x, 0.0f, kEps);
  EXPECT_NEAR(q.z, 0.0f, kEps);
  EXPECT_NEAR(q.y / q.w, std::tan(glm::radians(22.5f)), 1e-4f);  // symmetric blend: half the angle
  const glm::vec4 end = scene::sampleChannel(channel, 1.0f);
  EXPECT_NEAR(end.y, kHalfSqrt2, kEps);
  EXPECT_NEAR(end.w, kHalfSqrt2, kEps);
}

TEST(Animation, ClampsBeforeTheFirstAndAfterTheLastKey) {
  scene::Scene scene = loadAnimated();
  scene::evaluateAnimations(scene, -3.0f);
  expectNear(position(scene, "translated"), {0, 0, 0});
  expectNear(position(scene, "spline"), {0, 0, 0});
  scene::evaluateAnimations(scene, 7.0f);
  expectNear(position(scene, "translated"), {4, 2, 0});
  expectNear(position(scene, "spline"), {4, 0, 0});
  expectNear(position(scene, "child"), {1, 10, 0});
  // Nothing moves between two times past the end.
  EXPECT_FALSE(scene::evaluateAnimations(scene, 8.0f));
}

TEST(Animation, LoopWrapsModuloTheLongestDuration) {
  scene::Scene scene = loadAnimated();
  scene::evaluateAnimations(scene, 5.0f, /*loop=*/true);  // 5 mod 2 = 1
  expectNear(position(scene, "translated"), {2, 1, 0});
  scene::evaluateAnimations(scene, -0.5f, /*loop=*/true);  // wraps to 1.5
  expectNear(position(scene, "translated"), {3, 1.5f, 0});

  // A second, shorter animation wraps with the longest one (4 s), not its own length.
  Doc d = animatedDoc();
  addChannel(d, kStatic, "translation", "LINEAR", {0, 4}, {0, 0, -5, 0, 0, -9}, 1);
  TempDir dir;
  Result<scene::Scene> two = loadBytes(dir, d.gltf(), "two.gltf");
  ASSERT_TRUE(two.ok()) << two.error().message;
  ASSERT_EQ(two->animations.size(), 2u);
  scene::evaluateAnimations(*two, 7.0f, true);  // 7 mod 4 = 3
  expectNear(position(*two, "translated"), {4, 2, 0});
  expectNear(position(*two, "static"), {0, 0, -8});
}

TEST(Animation, ChildInheritsTheParentsAnimatedTransform) {
  scene::Scene scene = loadAnimated();
  scene::evaluateAnimations(scene, 1.0f);
  expectNear(position(scene, "child"), {1, 5, 0});
  scene::evaluateAnimations(scene, 2.0f);
  expectNear(position(scene, "child"), {1, 10, 0});
}

TEST(Animation, StaticInstancesKeepTheirTransform) {
  scene::Scene scene = loadAnimated();
  const glm::mat4 before = instance(scene, "static").worldFromObject;
  scene::evaluateAnimations(scene, 1.3f);
  EXPECT_EQ(instance(scene, "static").worldFromObject, before);
  scene::Scene still;
  EXPECT_FALSE(scene::evaluateAnimations(still, 1.0f));
}

TEST(Animation, PlacementFromASceneFileIsKept) {
  scene::Scene model = loadAnimated();
  scene::Scene world;
  world.nodes.push_back({});  // something already there: indices must be re-based
  const glm::mat4 placement = glm::translate(glm::mat4(1.0f), glm::vec3(100, 0, 0));
  scene::appendScene(world, std::move(model), placement);
  ASSERT_TRUE(scene::validate([&] {
                scene::Scene s = world;
                s.cameras.push_back({});
                return s;
              }())
                  .ok());
  scene::evaluateAnimations(world, 1.0f);
  expectNear(position(world, "translated"), {102, 1, 0});
  expectNear(position(world, "child"), {101, 5, 0});
  expectNear(position(world, "static"), {100, 0, -5});
}

// A skinned model placed by a scene file: its skin, joints and the lights and cameras on its nodes
// come along re-based, and the posed mesh is the model's own pose moved by the placement.
TEST(Animation, PlacedSkinsLightsAndCamerasFollowThePlacement) {
  const fs::path file = "/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf";
  if (!fs::exists(file)) GTEST_SKIP() << "assimp-testmodels is not installed";
  auto loaded = scene::loadScene(file.string());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  scene::Scene model = *loaded;
  const uint32_t lightNode = model.skins[0].joints.back();
  model.lights.push_back({});
  model.lights.back().node = int32_t(lightNode);
  model.cameras.push_back({});
  model.cameras.back().node = int32_t(lightNode);
  scene::Scene world;
  world.nodes.push_back({});  // something already there: indices must be re-based
  world.skins.push_back({"other", {0}, {glm::mat4(1.0f)}});
  const glm::vec3 offset(100, 0, -3);
  scene::appendScene(world, model, glm::translate(glm::mat4(1.0f), offset));
  ASSERT_TRUE(scene::validate(world).ok()) << scene::validate(world).error().message;
  for (float t : {0.0f, 1.3f}) {
    scene::Scene alone = model, placed = world;
    scene::evaluateAnimations(alone, t);
    scene::evaluateAnimations(placed, t);
    const scene::Instance& a = alone.instances[0];
    const scene::Instance& b = placed.instances[0];
    ASSERT_EQ(b.skin, 1);
    const scene::Primitive pa = scene::deformPrimitive(alone, a, alone.meshes[a.mesh].primitives[0]);
    const scene::Primitive pb = scene::deformPrimitive(placed, b, placed.meshes[b.mesh].primitives[0]);
    ASSERT_EQ(pa.positions.size(), pb.positions.size());
    for (size_t i = 0; i < pa.positions.size(); ++i) expectNear(pb.positions[i], pa.positions[i] + offset);
    expectNear(placed.lights.back().position, alone.lights.back().position + offset);
    expectNear(placed.cameras.back().position, alone.cameras.back().position + offset);
  }
}

// glTF-Validator: ANIMATION_CHANNEL_TARGET_NODE_WEIGHTS_NO_MORPHS is an error (weights channels on
// morphed meshes are played: tests/unit/test_skinning.cpp).
TEST(Animation, MorphWeightsOfAMeshWithoutTargetsAreRefused) {
  Doc d = quadDoc();
  addChannel(d, 0, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0});
  const int input = d.floats({0, 1}, "SCALAR", 1), output = d.floats({0, 1}, "SCALAR", 1);
  d.j["animations"][0]["samplers"].push_back({{"input", input}, {"output", output}});
  d.j["animations"][0]["channels"].push_back({{"sampler", 1}, {"target", {{"node", 0}, {"path", "weights"}}}});
  TempDir dir;
  expectRefused(loadBytes(dir, d.gltf()), "whose mesh has no morph targets");
}

TEST(Animation, RejectsNonIncreasingTimes) {
  TempDir dir;
  Doc d = quadDoc();
  addChannel(d, 0, "translation", "LINEAR", {0, 1, 1}, {0, 0, 0, 1, 0, 0, 2, 0, 0});
  expectRefused(loadBytes(dir, d.gltf()), "animations[0].samplers[0].input: key 2 at 1 is not after key 1 at 1");
  Doc backwards = quadDoc();
  addChannel(backwards, 0, "translation", "LINEAR", {1, 0.5f}, {0, 0, 0, 1, 0, 0});
  expectRefused(loadBytes(dir, backwards.gltf()), "animations[0].samplers[0].input: key 1 at 0.5 is not after");
}

TEST(Animation, RejectsNegativeTimes) {
  TempDir dir;
  Doc d = quadDoc();
  addChannel(d, 0, "translation", "LINEAR", {-1, 1}, {0, 0, 0, 1, 0, 0});
  expectRefused(loadBytes(dir, d.gltf()), "animations[0].samplers[0].input: key 0 is at -1, before 0");
}

TEST(Animation, RejectsWrongOutputCount) {
  TempDir dir;
  Doc d = quadDoc();
  addChannel(d, 0, "translation", "LINEAR", {0, 1, 2}, {0, 0, 0, 1, 0, 0});
  expectRefused(loadBytes(dir, d.gltf()),
                "animations[0].channels[0]: sampler 0 output accessor 5 has 2 elements, 3 keys of translation need 3");
  // CUBICSPLINE needs in-tangent, value and out-tangent per key.
  Doc cubic = quadDoc();
  addChannel(cubic, 0, "translation", "CUBICSPLINE", {0, 1}, {0, 0, 0, 1, 0, 0});
  expectRefused(loadBytes(dir, cubic.gltf()), "2 keys of translation need 6");
}

TEST(Animation, RejectsBadNodeIndex) {
  TempDir dir;
  Doc d = quadDoc();
  addChannel(d, 7, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0});
  expectRefused(loadBytes(dir, d.gltf()), "animations[0].channels[0].target.node: node 7 does not exist");
}

TEST(Animation, RejectsBadSamplerAndInterpolation) {
  TempDir dir;
  Doc d = quadDoc();
  addChannel(d, 0, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0});
  d.j["animations"][0]["channels"][0]["sampler"] = 3;
  expectRefused(loadBytes(dir, d.gltf()), "animations[0].channels[0].sampler: sampler 3 does not exist");
  // An interpolation glTF 2.0 does not define is only a warning in the validator: read as LINEAR.
  Doc interp = quadDoc();
  addChannel(interp, 0, "translation", "BOUNCY", {0, 1}, {0, 0, 0, 1, 0, 0});
  Result<scene::Scene> s = loadBytes(dir, interp.gltf());
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_EQ(s->animations.size(), 1u);
  EXPECT_EQ(s->animations[0].channels[0].interp, scene::AnimationChannel::Linear);
}

TEST(Animation, RejectsAnimatedMatrixNode) {
  TempDir dir;
  Doc d = quadDoc();
  d.node(0)["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  addChannel(d, 0, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0});
  expectRefused(loadBytes(dir, d.gltf()), "matrix");
}

// Every animated glTF 2.0 file in Debian's assimp-testmodels loads and plays without NaN.
TEST(AnimationTestModels, AnimatedModelsEvaluateWithoutNaN) {
  const fs::path root = "/usr/share/assimp/models/glTF2";
  std::error_code ec;
  if (!fs::is_directory(root, ec)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const log::Level previous = log::level();
  log::setLevel(log::Level::Error);
  size_t animated = 0;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const std::string ext = it->path().extension().string();
    if (!it->is_regular_file() || (ext != ".gltf" && ext != ".glb")) continue;
    Result<scene::Scene> scene = scene::loadGltf(it->path());
    if (!scene.ok() || !scene->animated()) continue;
    ++animated;
    float duration = 0.0f;
    for (const scene::Animation& a : scene->animations) duration = std::max(duration, a.duration);
    for (float t : {-1.0f, 0.0f, 0.37f * duration, 0.5f * duration, duration, duration + 1.0f}) {
      scene::evaluateAnimations(*scene, t, t < 0.0f);
      for (const scene::SceneNode& node : scene->nodes)
        EXPECT_TRUE(finite(node.worldFromNode)) << it->path() << " node " << node.name << " t=" << t;
      for (const scene::Instance& inst : scene->instances)
        EXPECT_TRUE(finite(inst.worldFromObject)) << it->path() << " instance " << inst.name << " t=" << t;
    }
  }
  log::setLevel(previous);
  std::printf("animated glTF test models: %zu\n", animated);
  // Debian 12: simple_skin (a rotating joint); AnimatedMorphCube only animates morph weights.
  const fs::path skin = root / "simple_skin/simple_skin.gltf";
  if (fs::exists(skin)) {
    EXPECT_GE(animated, 1u);
  }
}

}  // namespace
