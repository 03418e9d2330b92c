#include "scene/scene_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>
#include <string_view>

#include <stb/stb_image.h>  // stbi_info only: the implementation lives in core/image_io.cpp
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "core/log.h"
#include "scene/builtin.h"
#include "scene/loader.h"
#include "scene/merge.h"

namespace rayster::scene {
namespace fs = std::filesystem;
using nlohmann::json;
namespace {

// An equirect map past 16k x 8k is far beyond what lighting needs and costs gigabytes as floats.
constexpr int kMaxEnvironmentSide = 16384;

std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}
std::string element(const std::string& path, size_t i) { return fmt::format("{}[{}]", path, i); }

// Walks the JSON with typed accessors that name the file and JSON path in every error. Accessors
// leave their output untouched when the key is absent, so callers pre-fill defaults.
class Reader {
 public:
  Reader(std::string file, fs::path dir) : file_(std::move(file)), dir_(std::move(dir)) {}

  const std::string& file() const { return file_; }
  const fs::path& dir() const { return dir_; }

  Error error(const std::string& path, std::string_view what) const {
    return makeError(ExitCode::BadInput, "{}: {} {}", file_, path, what);
  }
  Status require(bool ok, const std::string& path, std::string_view what) const {
    if (!ok) return error(path, what);
    return okStatus();
  }

  Status object(const json& j, const std::string& path, std::initializer_list<std::string_view> known) const {
    if (!j.is_object()) return error(path.empty() ? "top level" : path, "must be an object");
    for (auto it = j.begin(); it != j.end(); ++it)
      if (std::find(known.begin(), known.end(), it.key()) == known.end())
        log::warn("{}: unknown key {} ignored", file_, child(path, it.key()));
    return okStatus();
  }

  Status number(const json& obj, std::string_view key, const std::string& path, float& out) const {
    auto it = obj.find(key);
    if (it == obj.end()) return okStatus();
    if (!it->is_number()) return error(child(path, key), "must be a number");
    const double value = it->get<double>();
    if (!std::isfinite(value) || std::abs(value) > FLT_MAX) return error(child(path, key), "must be a finite number");
    out = static_cast<float>(value);
    return okStatus();
  }

  // Exactly n numbers; n is 3 or 4.
  template <int N>
  Status vec(const json& obj, std::string_view key, const std::string& path, glm::vec<N, float>& out) const {
    auto it = obj.find(key);
    if (it == obj.end()) return okStatus();
    const std::string where = child(path, key);
    const std::string expected = fmt::format("must be an array of {} numbers", N);
    if (!it->is_array() || it->size() != N) return error(where, expected);
    glm::vec<N, float> value;
    for (int i = 0; i < N; ++i) {
      const json& v = (*it)[i];
      if (!v.is_number() || !std::isfinite(v.get<double>()) || std::abs(v.get<double>()) > FLT_MAX)
        return error(where, expected);
      value[i] = static_cast<float>(v.get<double>());
    }
    out = value;
    return okStatus();
  }

  Status string(const json& obj, std::string_view key, const std::string& path, std::string& out) const {
    auto it = obj.find(key);
    if (it == obj.end()) return okStatus();
    if (!it->is_string()) return error(child(path, key), "must be a string");
    out = it->get<std::string>();
    return okStatus();
  }

  // An optional array: absent is empty, anything else must be an array.
  Result<const json*> array(const json& obj, std::string_view key, const std::string& path) const {
    static const json kEmpty = json::array();
    auto it = obj.find(key);
    if (it == obj.end()) return &kEmpty;
    if (!it->is_array()) return error(child(path, key), "must be an array");
    return &*it;
  }

 private:
  std::string file_;
  fs::path dir_;
};

Status checkNonNegative(const Reader& r, std::string_view key, const std::string& path, float v) {
  return r.require(v >= 0.0f, child(path, key), fmt::format("must not be negative (is {})", v));
}

// translate * rotate * scale, so a model is scaled about its own origin, then turned, then placed.
Result<glm::mat4> readTransform(const Reader& r, const json& model, const std::string& path) {
  glm::vec3 translate(0.0f), rotate(0.0f), scale(1.0f);
  glm::vec4 axisAngle(0.0f);
  RAYSTER_TRY(r.vec(model, "translate", path, translate));
  RAYSTER_TRY(r.vec(model, "rotate", path, rotate));
  RAYSTER_TRY(r.vec(model, "rotateAxisAngle", path, axisAngle));
  RAYSTER_TRY(r.require(!(model.contains("rotate") && model.contains("rotateAxisAngle")), path,
                        "must have \"rotate\" or \"rotateAxisAngle\", not both"));
  if (auto it = model.find("scale"); it != model.end()) {
    if (it->is_number()) {
      float s = 1.0f;
      RAYSTER_TRY(r.number(model, "scale", path, s));
      scale = glm::vec3(s);
    } else {
      Status status = r.vec(model, "scale", path, scale);
      if (!status.ok()) return r.error(child(path, "scale"), "must be a number or an array of 3 numbers");
    }
    RAYSTER_TRY(r.require(scale.x != 0.0f && scale.y != 0.0f && scale.z != 0.0f, child(path, "scale"),
                          "must not be zero (it would flatten the model)"));
  }
  glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
  if (model.contains("rotateAxisAngle")) {
    const glm::vec3 axis(axisAngle);
    RAYSTER_TRY(r.require(glm::length(axis) > 0.0f, child(path, "rotateAxisAngle"), "has a zero-length axis"));
    m = glm::rotate(m, glm::radians(axisAngle.w), glm::normalize(axis));
  } else {
    // Euler angles applied about x, then y, then z (fixed axes): R = Rz * Ry * Rx.
    m = glm::rotate(m, glm::radians(rotate.z), glm::vec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(rotate.y), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(rotate.x), glm::vec3(1, 0, 0));
  }
  return glm::scale(m, scale);
}

Status readModel(const Reader& r, const json& model, const std::string& path, Scene& scene) {
  RAYSTER_TRY(r.object(model, path, {"path", "translate", "rotate", "rotateAxisAngle", "scale", "name"}));
  RAYSTER_TRY(r.require(model.contains("path"), path, "needs a \"path\""));
  std::string ref, name;
  RAYSTER_TRY(r.string(model, "path", path, ref));
  RAYSTER_TRY(r.string(model, "name", path, name));
  Result<glm::mat4> transform = readTransform(r, model, path);
  if (!transform) return transform.error();

  Result<Scene> loaded = Error{};
  if (ref.rfind("builtin:", 0) == 0) {
    loaded = isBuiltinModel(ref) ? makeBuiltinModel(ref) : makeBuiltinScene(ref);
  } else {
    Result<fs::path> file = resolveRelativePath(r.dir(), ref, fmt::format("{}: {}", r.file(), child(path, "path")));
    if (!file) return file.error();
    loaded = loadModelFile(*file);
  }
  if (!loaded) return makeError(loaded.error().code, "{}: {}: {}", r.file(), path, loaded.error().message);
  Scene model3d = std::move(*loaded);
  if (!name.empty()) {
    // A single-instance model takes the name; several keep theirs under it ("car/wheel").
    for (Instance& instance : model3d.instances)
      instance.name = model3d.instances.size() == 1 ? name : fmt::format("{}/{}", name, instance.name);
  }
  appendScene(scene, std::move(model3d), *transform);
  return okStatus();
}

Result<Light> readLight(const Reader& r, const json& j, const std::string& path) {
  RAYSTER_TRY(r.object(j, path,
                       {"type", "name", "position", "direction", "color", "intensity", "radius", "angularRadius",
                        "innerConeAngle", "outerConeAngle"}));
  Light light;
  std::string type;
  RAYSTER_TRY(r.string(j, "type", path, type));
  if (type == "point")
    light.type = LightType::Point;
  else if (type == "spot")
    light.type = LightType::Spot;
  else if (type == "directional")
    light.type = LightType::Directional;
  else
    return r.error(child(path, "type"), "must be \"point\", \"spot\" or \"directional\"");
  RAYSTER_TRY(r.string(j, "name", path, light.name));
  RAYSTER_TRY(r.vec(j, "position", path, light.position));
  RAYSTER_TRY(r.vec(j, "direction", path, light.direction));
  RAYSTER_TRY(r.require(glm::length(light.direction) > 0.0f, child(path, "direction"), "must not be zero"));
  light.direction = glm::normalize(light.direction);
  RAYSTER_TRY(r.vec(j, "color", path, light.color));
  RAYSTER_TRY(r.require(glm::all(glm::greaterThanEqual(light.color, glm::vec3(0.0f))), child(path, "color"),
                        "must not be negative"));
  RAYSTER_TRY(r.number(j, "intensity", path, light.intensity));
  RAYSTER_TRY(checkNonNegative(r, "intensity", path, light.intensity));
  RAYSTER_TRY(r.number(j, "radius", path, light.radius));
  RAYSTER_TRY(checkNonNegative(r, "radius", path, light.radius));
  float angular = glm::degrees(light.angularRadius), inner = glm::degrees(light.innerConeAngle),
        outer = glm::degrees(light.outerConeAngle);
  RAYSTER_TRY(r.number(j, "angularRadius", path, angular));
  RAYSTER_TRY(
      r.require(angular >= 0.0f && angular < 90.0f, child(path, "angularRadius"), "must be between 0 and 90 degrees"));
  RAYSTER_TRY(r.number(j, "innerConeAngle", path, inner));
  RAYSTER_TRY(r.number(j, "outerConeAngle", path, outer));
  RAYSTER_TRY(r.require(outer > 0.0f && outer <= 90.0f, child(path, "outerConeAngle"),
                        "must be above 0 and at most 90 degrees"));
  RAYSTER_TRY(r.require(inner >= 0.0f && inner <= outer, child(path, "innerConeAngle"),
                        "must be between 0 and outerConeAngle"));
  light.angularRadius = glm::radians(angular);
  light.innerConeAngle = glm::radians(inner);
  light.outerConeAngle = glm::radians(outer);
  return light;
}

Result<Camera> readCamera(const Reader& r, const json& j, const std::string& path) {
  RAYSTER_TRY(r.object(j, path, {"name", "position", "target", "up", "yfov", "znear", "zfar"}));
  Camera camera;
  float yFov = glm::degrees(camera.yFov);
  RAYSTER_TRY(r.string(j, "name", path, camera.name));
  RAYSTER_TRY(r.vec(j, "position", path, camera.position));
  RAYSTER_TRY(r.vec(j, "target", path, camera.target));
  RAYSTER_TRY(r.vec(j, "up", path, camera.up));
  RAYSTER_TRY(r.number(j, "yfov", path, yFov));
  RAYSTER_TRY(r.number(j, "znear", path, camera.zNear));
  RAYSTER_TRY(r.number(j, "zfar", path, camera.zFar));
  RAYSTER_TRY(r.require(camera.position != camera.target, path, "position and target must differ"));
  RAYSTER_TRY(r.require(glm::length(glm::cross(camera.target - camera.position, camera.up)) > 0.0f, child(path, "up"),
                        "must not be zero or parallel to the view direction"));
  RAYSTER_TRY(r.require(yFov > 0.0f && yFov < 180.0f, child(path, "yfov"), "must be between 0 and 180 degrees"));
  RAYSTER_TRY(r.require(camera.zNear > 0.0f, child(path, "znear"), "must be positive"));
  RAYSTER_TRY(r.require(camera.zFar > camera.zNear, child(path, "zfar"), "must be greater than znear"));
  camera.yFov = glm::radians(yFov);
  return camera;
}

Status readEnvironmentMap(const Reader& r, const std::string& ref, const std::string& path, Environment& env) {
  Result<fs::path> file = resolveRelativePath(r.dir(), ref, fmt::format("{}: {}", r.file(), path));
  if (!file) return file.error();
  std::string ext = file->extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  RAYSTER_TRY(r.require(ext == ".hdr" || ext == ".exr", path, "must name an equirectangular .hdr or .exr image"));
  std::error_code ec;
  RAYSTER_TRY(r.require(fs::is_regular_file(*file, ec), path, fmt::format("'{}': no such file", ref)));
  // Refuse absurd sizes from the header, before decoding allocates them.
  // Only a file that starts as Radiance HDR does ("#?") is handed to stbi_info: it would try any
  // other bytes as JPEG first, before the reader's stbDecodeHazard() check has seen them.
  int w = 0, h = 0, channels = 0;
  const bool radiance = [&] {
    char magic[2] = {};
    std::ifstream(*file, std::ios::binary).read(magic, 2);
    return magic[0] == '#' && magic[1] == '?';
  }();
  if (ext == ".hdr" && radiance && stbi_info(file->c_str(), &w, &h, &channels))
    RAYSTER_TRY(r.require(w <= kMaxEnvironmentSide && h <= kMaxEnvironmentSide, path,
                          fmt::format("'{}' is {}x{}, more than {} pixels per side", ref, w, h, kMaxEnvironmentSide)));
  Result<ImageF> image = readImageLinear(*file);
  if (!image) return makeError(ExitCode::BadInput, "{}: {}: {}", r.file(), path, image.error().message);
  RAYSTER_TRY(r.require(!image->empty() && image->width <= kMaxEnvironmentSide && image->height <= kMaxEnvironmentSide,
                        path,
                        fmt::format("'{}' is {}x{}: empty or more than {} pixels per side", ref, image->width,
                                    image->height, kMaxEnvironmentSide)));
  env.kind = Environment::Kind::Map;
  env.mapPath = file->string();
  env.width = image->width;
  env.height = image->height;
  const size_t pixels = static_cast<size_t>(image->width) * image->height;
  env.rgb.resize(pixels * 3);
  for (size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = image->rgba[i * 4 + c];
      env.rgb[i * 3 + c] = std::isfinite(v) ? std::max(v, 0.0f) : 0.0f;  // one NaN would poison every sample
    }
  return okStatus();
}

Status readEnvironment(const Reader& r, const json& j, Environment& env) {
  const std::string path = "environment";
  if (j.is_string()) {
    if (j == "black")
      env.kind = Environment::Kind::Black;
    else if (j == "sky")
      env.kind = Environment::Kind::Sky;
    else
      return r.error(path, "must be \"black\", \"sky\" or an object");
    return okStatus();
  }
  RAYSTER_TRY(r.object(j, path, {"map", "sky", "intensity", "rotation"}));
  RAYSTER_TRY(r.require(j.contains("map") != j.contains("sky"), path, "must have either \"map\" or \"sky\""));
  RAYSTER_TRY(r.number(j, "intensity", path, env.intensity));
  RAYSTER_TRY(checkNonNegative(r, "intensity", path, env.intensity));
  float rotation = 0.0f;
  RAYSTER_TRY(r.number(j, "rotation", path, rotation));
  env.rotation = glm::radians(rotation);
  if (j.contains("sky")) {
    const json& sky = j["sky"];
    const std::string skyPath = child(path, "sky");
    RAYSTER_TRY(r.object(sky, skyPath, {"zenith", "horizon", "ground"}));
    RAYSTER_TRY(r.vec(sky, "zenith", skyPath, env.zenith));
    RAYSTER_TRY(r.vec(sky, "horizon", skyPath, env.horizon));
    RAYSTER_TRY(r.vec(sky, "ground", skyPath, env.ground));
    env.kind = Environment::Kind::Sky;
    return okStatus();
  }
  std::string ref;
  RAYSTER_TRY(r.string(j, "map", path, ref));
  return readEnvironmentMap(r, ref, child(path, "map"), env);
}

Status readCameraPath(const Reader& r, const json& keys, std::vector<CameraKey>& out) {
  for (size_t i = 0; i < keys.size(); ++i) {
    const std::string path = element("cameraPath", i);
    RAYSTER_TRY(r.object(keys[i], path, {"time", "position", "target"}));
    for (const char* required : {"time", "position", "target"})
      RAYSTER_TRY(r.require(keys[i].contains(required), path, fmt::format("needs \"{}\"", required)));
    CameraKey key;
    RAYSTER_TRY(r.number(keys[i], "time", path, key.time));
    RAYSTER_TRY(r.vec(keys[i], "position", path, key.position));
    RAYSTER_TRY(r.vec(keys[i], "target", path, key.target));
    RAYSTER_TRY(r.require(out.empty() || key.time > out.back().time, child(path, "time"),
                          "must be greater than the previous key's time"));
    out.push_back(key);
  }
  return okStatus();
}

// The position of the first byte that is not part of well-formed UTF-8 (RFC 3629: no overlong
// forms, no surrogates, nothing past U+10FFFF), or npos.
size_t firstInvalidUtf8(std::string_view t) {
  size_t i = 0;
  while (i < t.size()) {
    const auto b = [&](size_t k) { return uint8_t(t[k]); };
    const uint8_t c = b(i);
    size_t n = c < 0x80                   ? 1
               : (c >= 0xC2 && c <= 0xDF) ? 2
               : (c >= 0xE0 && c <= 0xEF) ? 3
               : (c >= 0xF0 && c <= 0xF4) ? 4
                                          : 0;
    if (n == 0 || i + n > t.size()) return i;
    for (size_t k = 1; k < n; ++k)
      if ((b(i + k) & 0xC0) != 0x80) return i;
    if ((c == 0xE0 && b(i + 1) < 0xA0) || (c == 0xED && b(i + 1) > 0x9F) || (c == 0xF0 && b(i + 1) < 0x90) ||
        (c == 0xF4 && b(i + 1) > 0x8F))
      return i;
    i += n;
  }
  return std::string_view::npos;
}

Result<json> parseJson(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(ExitCode::BadInput, "cannot read scene '{}': no such file", path.string());
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // JSON is UTF-8 (RFC 8259); say where it is not, without echoing the bytes.
  if (const size_t bad = firstInvalidUtf8(text); bad != std::string_view::npos) {
    const size_t line = size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(bad), '\n')) + 1;
    const size_t lineStart = text.rfind('\n', bad == 0 ? 0 : bad - 1);
    const size_t column = lineStart == std::string::npos || bad == 0 ? bad + 1 : bad - lineStart;
    return makeError(ExitCode::BadInput, "{}: not UTF-8 text: byte 0x{:02X} at byte offset {} (line {}, column {})",
                     path.filename().string(), unsigned(uint8_t(text[bad])), bad, line, column);
  }
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    // e.what() is "[json.exception.parse_error.101] parse error at line 3, column 1: ..."; keep the
    // human part, which names the position. A number too large for a double is out_of_range.406
    // ("number overflow parsing '1e400'"), not a parse_error: every json::exception is bad input.
    std::string what = e.what();
    if (const size_t bracket = what.find("] "); what.rfind("[json.", 0) == 0 && bracket != std::string::npos)
      what = what.substr(bracket + 2);
    return makeError(ExitCode::BadInput, "{}: invalid JSON: {}", path.filename().string(), what);
  }
}

}  // namespace

Result<Scene> loadSceneFile(const fs::path& path) {
  Result<json> parsed = parseJson(path);
  if (!parsed) return parsed.error();
  const json& root = *parsed;
  const Reader r(path.filename().string(), path.parent_path().empty() ? fs::path(".") : path.parent_path());
  RAYSTER_TRY(r.object(root, "", {"name", "models", "lights", "cameras", "environment", "ambient", "cameraPath"}));

  Scene scene;
  scene.name = path.stem().string();
  RAYSTER_TRY(r.string(root, "name", "", scene.name));
  RAYSTER_TRY(r.require(root.contains("models") && root["models"].is_array() && !root["models"].empty(), "models",
                        "must be a non-empty array of models"));
  // Scene-level settings are read first so that they take precedence over what models bring.
  if (root.contains("environment")) RAYSTER_TRY(readEnvironment(r, root["environment"], scene.environment));
  RAYSTER_TRY(r.vec(root, "ambient", "", scene.ambient));
  RAYSTER_TRY(
      r.require(glm::all(glm::greaterThanEqual(scene.ambient, glm::vec3(0.0f))), "ambient", "must not be negative"));
  Result<const json*> cameraPath = r.array(root, "cameraPath", "");
  if (!cameraPath) return cameraPath.error();
  RAYSTER_TRY(readCameraPath(r, **cameraPath, scene.cameraPath));

  Result<const json*> lights = r.array(root, "lights", "");
  if (!lights) return lights.error();
  for (size_t i = 0; i < (*lights)->size(); ++i) {
    Result<Light> light = readLight(r, (**lights)[i], element("lights", i));
    if (!light) return light.error();
    scene.lights.push_back(std::move(*light));
  }
  // The file's cameras go first: camera 0 is what renders by default.
  Result<const json*> cameras = r.array(root, "cameras", "");
  if (!cameras) return cameras.error();
  for (size_t i = 0; i < (*cameras)->size(); ++i) {
    Result<Camera> camera = readCamera(r, (**cameras)[i], element("cameras", i));
    if (!camera) return camera.error();
    scene.cameras.push_back(std::move(*camera));
  }

  const json& models = root["models"];
  for (size_t i = 0; i < models.size(); ++i) RAYSTER_TRY(readModel(r, models[i], element("models", i), scene));
  return scene;
}

}  // namespace rayster::scene
