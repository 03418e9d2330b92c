// The glTF 2.0 schema for meshes, nodes, scenes, skins, animations and cameras, with the
// validator's link checks between them (a node's weights against its mesh's morph targets, a
// channel's output count against its input and path, one parent per node, ...).
#include <cmath>
#include <map>
#include <set>

#include "scene/gltf_schema.h"

namespace rayster::scene::gltf::schema {
namespace {

// POSITION, NORMAL, TANGENT, TEXCOORD_n, COLOR_n, JOINTS_n, WEIGHTS_n, or an application-specific
// name starting with '_'. `set` gets n (or -1) and `base` the name before it.
bool attributeName(const std::string& name, std::string& base, long& set) {
  set = -1;
  base = name;
  if (!name.empty() && name[0] == '_') return true;
  if (name == "POSITION" || name == "NORMAL" || name == "TANGENT") return true;
  const size_t u = name.rfind('_');
  if (u == std::string::npos || u + 1 >= name.size() || name.size() - u > 6) return false;
  for (size_t i = u + 1; i < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  if (name.size() - u > 2 && name[u + 1] == '0') return false;  // no leading zeros
  base = name.substr(0, u);
  set = std::stol(name.substr(u + 1));
  return base == "TEXCOORD" || base == "COLOR" || base == "JOINTS" || base == "WEIGHTS";
}

// The accessor types each standard attribute may have (component types vary with
// KHR_mesh_quantization, so only the type is checked here; the readers check the rest).
bool typeAllowed(const std::string& base, const std::string& type) {
  if (base == "POSITION" || base == "NORMAL") return type == "VEC3";
  if (base == "TANGENT" || base == "JOINTS" || base == "WEIGHTS") return type == "VEC4";
  if (base == "TEXCOORD") return type == "VEC2";
  if (base == "COLOR") return type == "VEC3" || type == "VEC4";
  return true;
}

// Every textureInfo in a material (core and the KHR_materials_* extensions, which the validator
// knows; others may mean something else by a "texCoord"): objects named "...Texture" with an index.
void texCoordsOf(const Json& o, const std::string& path, std::vector<std::pair<std::string, int64_t>>& out,
                 bool inExtensions = false) {
  if (!o.is_object()) return;
  for (auto it = o.begin(); it != o.end(); ++it) {
    const std::string& key = it.key();
    if (key == "extras" || !it.value().is_object()) continue;
    if (inExtensions && key.rfind("KHR_materials_", 0) != 0) continue;
    const std::string p = Checker::at(path, key.c_str());
    const bool texture = key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0;
    if (texture && it.value().contains("index")) {
      int64_t texCoord = it.value().value("texCoord", int64_t(0));
      const Json* ext = Checker::find(it.value(), "extensions");
      if (const Json* t = ext ? Checker::find(*ext, "KHR_texture_transform") : nullptr)
        texCoord = t->value("texCoord", texCoord);
      out.emplace_back(p, texCoord);
    } else {
      texCoordsOf(it.value(), p, out, key == "extensions");
    }
  }
}

Status noStride(const Checker& c, uint64_t accessor, const std::string& path, const char* what) {
  const Json& a = c.element("accessors", accessor);
  if (const Json* view = Checker::find(a, "bufferView"))
    if (Checker::find(c.element("bufferViews", view->get<size_t>()), "byteStride"))
      return c.fail(path, "accessor {} is in buffer view {}, which has a byteStride; {} must not", accessor,
                    view->get<uint64_t>(), what);
  return okStatus();
}

Status checkPrimitive(const Checker& c, const Json& prim, const std::string& p, size_t& targets,
                      std::map<uint64_t, std::set<uint64_t>>& attributeViews) {
  const Json* attributes = Checker::find(prim, "attributes");
  if (!attributes) return c.fail(p, "attributes is required");
  const std::string ap = Checker::at(p, "attributes");
  if (attributes->empty()) return c.fail(ap, "is empty");
  std::map<std::string, std::set<long>> sets;
  // Every attribute has POSITION's count (or, without POSITION, the first one's).
  int64_t vertexCount = -1;
  if (const Json* position = Checker::find(*attributes, "POSITION");
      position && position->is_number_unsigned() && position->get<uint64_t>() < c.count("accessors"))
    vertexCount = c.element("accessors", position->get<size_t>())["count"].get<int64_t>();
  for (auto it = attributes->begin(); it != attributes->end(); ++it) {
    const std::string name = it.key(), at = Checker::at(ap, name.c_str());
    std::string base;
    long set = 0;
    if (!attributeName(name, base, set)) return c.fail(at, "is not a glTF attribute name (custom ones start with _)");
    if (set >= 0) sets[base].insert(set);
    RAYSTER_TRY(c.ref(*attributes, name.c_str(), ap, "accessors", true));
    const uint64_t index = it.value().get<uint64_t>();
    const Json& a = c.element("accessors", index);
    const std::string type = a["type"].get<std::string>();
    if (!typeAllowed(base, type)) return c.fail(at, "accessor {} has type {}, which {} cannot have", index, type, base);
    if (a["componentType"].get<int64_t>() == 5125)
      return c.fail(at, "accessor {} is unsigned int, which vertex attributes cannot be", index);
    const int64_t count = a["count"].get<int64_t>();
    if (vertexCount >= 0 && count != vertexCount)
      return c.fail(at, "accessor {} has {} elements, {} has {}", index, count,
                    attributes->contains("POSITION") ? "POSITION" : "the primitive's first attribute", vertexCount);
    vertexCount = count;
    if (const Json* view = Checker::find(a, "bufferView")) {
      const Json& v = c.element("bufferViews", view->get<size_t>());
      if ((v.value("byteOffset", uint64_t(0)) + a.value("byteOffset", uint64_t(0))) % 4 != 0)
        return c.fail(at, "accessor {} does not start on a 4-byte boundary, which vertex data must", index);
      if (!Checker::find(v, "byteStride")) attributeViews[view->get<uint64_t>()].insert(index);
    }
  }
  for (const auto& [base, used] : sets)
    if (*used.rbegin() + 1 != long(used.size()))
      return c.fail(ap, "{}_n sets are not numbered 0 to {} without gaps", base, used.size() - 1);
  if (sets["JOINTS"].size() != sets["WEIGHTS"].size())
    return c.fail(ap, "{} JOINTS_n sets but {} WEIGHTS_n sets", sets["JOINTS"].size(), sets["WEIGHTS"].size());

  RAYSTER_TRY(c.integer(prim, "mode", p, {0.0, 6.0}));
  RAYSTER_TRY(c.ref(prim, "material", p, "materials"));
  RAYSTER_TRY(c.ref(prim, "indices", p, "accessors"));
  if (const Json* indices = Checker::find(prim, "indices")) {
    const Json& a = c.element("accessors", indices->get<size_t>());
    const int64_t type = a["componentType"].get<int64_t>();
    if (a["type"] != "SCALAR" || (type != 5121 && type != 5123 && type != 5125) || a.value("normalized", false))
      return c.fail(Checker::at(p, "indices"), "accessor {} is not an unsigned byte, short or int SCALAR",
                    indices->get<uint64_t>());
    RAYSTER_TRY(noStride(c, indices->get<uint64_t>(), Checker::at(p, "indices"), "indices"));
  }
  // Texture coordinates the material's textures read must be there.
  if (const Json* material = Checker::find(prim, "material")) {
    // A clearcoat normal map needs a tangent space: TANGENT, or a normal map to generate one from
    // (MESH_PRIMITIVE_NO_TANGENT_SPACE).
    const Json& m = c.element("materials", material->get<size_t>());
    const Json* ext = Checker::find(m, "extensions");
    const Json* clearcoat = ext ? Checker::find(*ext, "KHR_materials_clearcoat") : nullptr;
    const bool needsTangents = clearcoat && clearcoat->contains("clearcoatNormalTexture");
    if (needsTangents && !attributes->contains("TANGENT") && !m.contains("normalTexture"))
      return c.fail(Checker::at(p, "material"),
                    "material {} needs a tangent space for its clearcoat normals, but the primitive has no "
                    "TANGENT and the material no normal map",
                    material->get<uint64_t>());
    std::vector<std::pair<std::string, int64_t>> uses;
    texCoordsOf(c.element("materials", material->get<size_t>()),
                fmt::format("materials[{}]", material->get<uint64_t>()), uses);
    for (const auto& [texture, set] : uses)
      if (!sets["TEXCOORD"].count(long(set)))
        return c.fail(Checker::at(p, "material"), "{} reads TEXCOORD_{}, which the primitive does not have", texture,
                      set);
  }
  targets = 0;
  if (const Json* t = Checker::find(prim, "targets")) {
    const std::string tp = Checker::at(p, "targets");
    if (!t->is_array() || t->empty()) return c.fail(tp, "is not a non-empty array");
    targets = t->size();
    for (size_t i = 0; i < t->size(); ++i) {
      const Json& target = (*t)[i];
      const std::string ti = Checker::at(tp, i);
      if (!target.is_object() || target.empty()) return c.fail(ti, "is not a non-empty object");
      for (auto it = target.begin(); it != target.end(); ++it) {
        RAYSTER_TRY(c.ref(target, it.key().c_str(), ti, "accessors", true));
        const std::string at = Checker::at(ti, it.key().c_str());
        if (!attributes->contains(it.key())) return c.fail(at, "the primitive has no {} attribute to morph", it.key());
        const Json& a = c.element("accessors", it.value().get<size_t>());
        if (a["count"].get<int64_t>() != vertexCount)
          return c.fail(at, "accessor {} has {} elements for {} vertices", it.value().get<uint64_t>(),
                        a["count"].get<int64_t>(), vertexCount);
      }
    }
  }
  return okStatus();
}

// Morph targets per mesh (from its first primitive; checkMeshes makes them all agree).
std::vector<size_t> meshTargets(const Checker& c) {
  std::vector<size_t> out;
  for (size_t m = 0; m < c.count("meshes"); ++m) {
    const Json& prims = c.element("meshes", m)["primitives"];
    const Json* t = prims.empty() ? nullptr : Checker::find(prims[0], "targets");
    out.push_back(t && t->is_array() ? t->size() : 0);
  }
  return out;
}

bool skinned(const Checker& c, size_t mesh) {
  for (const Json& prim : c.element("meshes", mesh)["primitives"])
    if (const Json* a = Checker::find(prim, "attributes"); a && a->contains("JOINTS_0")) return true;
  return false;
}

// parent[i]: node i's parent, -1 for a root; fails on a second parent or a cycle.
Status hierarchy(const Checker& c, std::vector<int64_t>& parent) {
  const size_t n = c.count("nodes");
  parent.assign(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const Json* children = Checker::find(c.element("nodes", i), "children");
    if (!children) continue;
    for (size_t k = 0; k < children->size(); ++k) {
      const size_t child = (*children)[k].get<size_t>();
      const std::string p = Checker::at(fmt::format("nodes[{}].children", i), k);
      if (child == i) return c.fail(p, "node {} is its own child", i);
      if (parent[child] >= 0) return c.fail(p, "node {} already has parent {}", child, parent[child]);
      parent[child] = int64_t(i);
    }
  }
  // With one parent each, a cycle is a walk up that never reaches a root.
  for (size_t i = 0; i < n; ++i) {
    size_t steps = 0;
    for (int64_t at = int64_t(i); at >= 0; at = parent[size_t(at)])
      if (++steps > n) return c.fail(fmt::format("nodes[{}]", i), "is part of a cycle of children");
  }
  return okStatus();
}

// A matrix glTF can decompose into translation, rotation and scale: affine (last row exactly
// 0 0 0 1, as the validator wants it), invertible, and without shear (its columns orthogonal; the
// validator accepts a shear of 1e-4 and refuses 3e-4, rounding is far below either).
bool decomposable(const Json& m) {
  double v[16];
  for (int i = 0; i < 16; ++i) v[i] = m[size_t(i)].get<double>();
  if (v[3] != 0.0 || v[7] != 0.0 || v[11] != 0.0 || v[15] != 1.0) return false;
  const double det =
      v[0] * (v[5] * v[10] - v[9] * v[6]) - v[4] * (v[1] * v[10] - v[9] * v[2]) + v[8] * (v[1] * v[6] - v[5] * v[2]);
  if (!std::isfinite(det) || det == 0.0) return false;
  auto dot = [&](int a, int b) {
    return v[a * 4] * v[b * 4] + v[a * 4 + 1] * v[b * 4 + 1] + v[a * 4 + 2] * v[b * 4 + 2];
  };
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      if (std::abs(dot(a, b)) > 2e-4 * std::sqrt(dot(a, a) * dot(b, b))) return false;
  return true;
}

Status checkNode(const Checker& c, size_t i, const std::vector<size_t>& targets) {
  const Json& n = c.element("nodes", i);
  const std::string p = fmt::format("nodes[{}]", i);
  RAYSTER_TRY(c.ref(n, "camera", p, "cameras"));
  RAYSTER_TRY(c.ref(n, "mesh", p, "meshes"));
  RAYSTER_TRY(c.ref(n, "skin", p, "skins"));
  RAYSTER_TRY(c.refs(n, "children", p, "nodes"));
  RAYSTER_TRY(c.numbers(n, "matrix", p, {16}));
  RAYSTER_TRY(c.numbers(n, "translation", p, {3}));
  RAYSTER_TRY(c.numbers(n, "rotation", p, {4}, {-1.0, 1.0}));
  RAYSTER_TRY(c.numbers(n, "scale", p, {3}));
  if (const Json* w = Checker::find(n, "weights")) {
    if (!w->is_array() || w->empty()) return c.fail(Checker::at(p, "weights"), "is not a non-empty array");
    RAYSTER_TRY(c.numbers(n, "weights", p, {w->size()}));
  }
  const Json* matrix = Checker::find(n, "matrix");
  if (matrix && (n.contains("translation") || n.contains("rotation") || n.contains("scale")))
    return c.fail(p, "has both a matrix and translation/rotation/scale");
  if (matrix && !decomposable(*matrix))
    return c.fail(Checker::at(p, "matrix"),
                  "is not a translation, rotation and scale (its last row must be 0 0 0 1 "
                  "and it must be invertible)");
  if (const Json* r = Checker::find(n, "rotation")) {
    double length2 = 0.0;
    for (const Json& x : *r) length2 += x.get<double>() * x.get<double>();
    // The validator's tolerance: |1 - length| up to 0.00769 passes.
    if (std::abs(1.0 - std::sqrt(length2)) > 0.00769)
      return c.fail(Checker::at(p, "rotation"), "has length {}, not a unit quaternion", std::sqrt(length2));
  }
  const Json* mesh = Checker::find(n, "mesh");
  if (n.contains("skin") && !mesh) return c.fail(Checker::at(p, "skin"), "is set but mesh is not");
  if (n.contains("skin") && !skinned(c, mesh->get<size_t>()))
    return c.fail(Checker::at(p, "skin"), "is set but mesh {} has no JOINTS_0", mesh->get<uint64_t>());
  if (const Json* w = Checker::find(n, "weights")) {
    const size_t want = mesh ? targets[mesh->get<size_t>()] : 0;
    if (w->size() != want) return c.fail(Checker::at(p, "weights"), "{} weights for {} morph targets", w->size(), want);
  }
  if (const Json* ext = Checker::find(n, "extensions"))
    if (const Json* light = Checker::find(*ext, "KHR_lights_punctual")) {
      const Json* top = Checker::find(c.root(), "extensions");
      const Json* lights = top ? Checker::find(*top, "KHR_lights_punctual") : nullptr;
      const Json* list = lights ? Checker::find(*lights, "lights") : nullptr;
      RAYSTER_TRY(c.indexInto(*light, "light", Checker::at(Checker::at(p, "extensions"), "KHR_lights_punctual"),
                              list && list->is_array() ? list->size() : 0, "lights", true));
    }
  return okStatus();
}

}  // namespace

Status checkMeshes(const Checker& c) {
  std::map<uint64_t, std::set<uint64_t>> attributeViews;  // buffer view -> vertex accessors without a stride
  for (size_t m = 0; m < c.count("meshes"); ++m) {
    const Json& mesh = c.element("meshes", m);
    const std::string p = fmt::format("meshes[{}]", m);
    const Json& prims = mesh["primitives"];  // checkJsonTypes: required, an array of objects
    if (prims.empty()) return c.fail(Checker::at(p, "primitives"), "is empty, need at least one primitive");
    size_t first = 0;
    for (size_t i = 0; i < prims.size(); ++i) {
      size_t targets = 0;
      const std::string pp = Checker::at(Checker::at(p, "primitives"), i);
      RAYSTER_TRY(checkPrimitive(c, prims[i], pp, targets, attributeViews));
      if (i == 0) first = targets;
      if (targets != first)
        return c.fail(pp, "has {} morph targets, primitive 0 has {} (all must have the same)", targets, first);
    }
    if (const Json* w = Checker::find(mesh, "weights")) {
      if (!w->is_array() || w->empty()) return c.fail(Checker::at(p, "weights"), "is not a non-empty array");
      RAYSTER_TRY(c.numbers(mesh, "weights", p, {w->size()}));
      if (w->size() != first)
        return c.fail(Checker::at(p, "weights"), "{} weights for {} morph targets", w->size(), first);
    }
  }
  for (const auto& [view, accessors] : attributeViews)
    if (accessors.size() > 1)
      return c.fail(fmt::format("bufferViews[{}]", view),
                    "holds {} vertex attribute accessors but no byteStride, which it needs then", accessors.size());
  return okStatus();
}

Status checkNodesAndScenes(const Checker& c) {
  const std::vector<size_t> targets = meshTargets(c);
  for (size_t i = 0; i < c.count("nodes"); ++i) RAYSTER_TRY(checkNode(c, i, targets));
  std::vector<int64_t> parent;
  RAYSTER_TRY(hierarchy(c, parent));
  for (size_t s = 0; s < c.count("scenes"); ++s) {
    const std::string p = fmt::format("scenes[{}]", s);
    RAYSTER_TRY(c.refs(c.element("scenes", s), "nodes", p, "nodes"));
    size_t k = 0;
    for (const Json& n : c.element("scenes", s).value("nodes", Json::array())) {
      if (parent[n.get<size_t>()] >= 0)
        return c.fail(Checker::at(Checker::at(p, "nodes"), k), "node {} is not a root (its parent is node {})",
                      n.get<uint64_t>(), parent[n.get<size_t>()]);
      ++k;
    }
  }
  return okStatus();
}

namespace {

Status checkSkins(const Checker& c, const std::vector<int64_t>& parent) {
  for (size_t s = 0; s < c.count("skins"); ++s) {
    const Json& skin = c.element("skins", s);
    const std::string p = fmt::format("skins[{}]", s);
    if (!skin.contains("joints")) return c.fail(p, "joints is required");
    RAYSTER_TRY(c.refs(skin, "joints", p, "nodes"));
    RAYSTER_TRY(c.ref(skin, "skeleton", p, "nodes"));
    RAYSTER_TRY(c.ref(skin, "inverseBindMatrices", p, "accessors"));
    const Json& joints = skin["joints"];
    if (const Json* ibm = Checker::find(skin, "inverseBindMatrices")) {
      const Json& a = c.element("accessors", ibm->get<size_t>());
      const std::string ip = Checker::at(p, "inverseBindMatrices");
      if (a["type"] != "MAT4" || a["componentType"] != 5126)
        return c.fail(ip, "accessor {} is not a float MAT4", ibm->get<uint64_t>());
      if (a["count"].get<size_t>() < joints.size())
        return c.fail(ip, "accessor {} has {} matrices for {} joints", ibm->get<uint64_t>(), a["count"].get<size_t>(),
                      joints.size());
      RAYSTER_TRY(noStride(c, ibm->get<uint64_t>(), ip, "inverse bind matrices"));
    }
    // The joints form one tree: they share the top-most ancestor, and a skeleton is an ancestor
    // (or one) of every joint.
    auto top = [&](int64_t n) {
      while (parent[size_t(n)] >= 0) n = parent[size_t(n)];
      return n;
    };
    const int64_t root = top(joints[0].get<int64_t>());
    for (size_t j = 1; j < joints.size(); ++j)
      if (top(joints[j].get<int64_t>()) != root)
        return c.fail(Checker::at(Checker::at(p, "joints"), j), "node {} has no common root with joint 0",
                      joints[j].get<int64_t>());
    if (const Json* skeleton = Checker::find(skin, "skeleton"))
      for (size_t j = 0; j < joints.size(); ++j) {
        int64_t n = joints[j].get<int64_t>();
        while (n >= 0 && n != skeleton->get<int64_t>()) n = parent[size_t(n)];
        if (n < 0)
          return c.fail(Checker::at(p, "skeleton"), "node {} is not an ancestor of joint {}", skeleton->get<int64_t>(),
                        joints[j].get<int64_t>());
      }
  }
  return okStatus();
}

Status checkAnimation(const Checker& c, size_t index, const std::vector<size_t>& targets) {
  const Json& anim = c.element("animations", index);
  const std::string p = fmt::format("animations[{}]", index);
  for (const char* key : {"channels", "samplers"}) {
    const Json* v = Checker::find(anim, key);
    if (!v) return c.fail(p, "{} is required", key);
    if (!v->is_array() || v->empty()) return c.fail(Checker::at(p, key), "is not a non-empty array");
    for (size_t i = 0; i < v->size(); ++i)
      if (!(*v)[i].is_object()) return c.fail(Checker::at(Checker::at(p, key), i), "is not an object");
  }
  const Json& samplers = anim["samplers"];
  for (size_t s = 0; s < samplers.size(); ++s) {
    const std::string sp = Checker::at(Checker::at(p, "samplers"), s);
    RAYSTER_TRY(c.ref(samplers[s], "input", sp, "accessors", true));
    RAYSTER_TRY(c.ref(samplers[s], "output", sp, "accessors", true));
    RAYSTER_TRY(c.string(samplers[s], "interpolation", sp));  // an unknown one is only a warning
    const Json& input = c.element("accessors", samplers[s]["input"].get<size_t>());
    if (input["type"] != "SCALAR" || input["componentType"] != 5126)
      return c.fail(Checker::at(sp, "input"), "accessor {} is not a float SCALAR",
                    samplers[s]["input"].get<uint64_t>());
    // Key times without min and max are an error to the validator, but absent bounds cannot
    // contradict the data (tests/unit/test_gltf_mutations.cpp lists the exception).
    const bool cubic = samplers[s].value("interpolation", "") == "CUBICSPLINE";
    if (cubic && input["count"].get<int64_t>() < 2)
      return c.fail(Checker::at(sp, "input"), "CUBICSPLINE needs at least 2 keys, accessor {} has 1",
                    samplers[s]["input"].get<uint64_t>());
    for (const char* key : {"input", "output"})
      RAYSTER_TRY(noStride(c, samplers[s][key].get<uint64_t>(), Checker::at(sp, key), "animation data"));
  }
  std::set<std::pair<int64_t, std::string>> seen;
  const Json& channels = anim["channels"];
  for (size_t ch = 0; ch < channels.size(); ++ch) {
    const Json& channel = channels[ch];
    const std::string cp = Checker::at(Checker::at(p, "channels"), ch);
    RAYSTER_TRY(c.indexInto(channel, "sampler", cp, samplers.size(), "samplers", true));
    const Json* target = Checker::find(channel, "target");
    if (!target) return c.fail(cp, "target is required");
    const std::string tp = Checker::at(cp, "target");
    if (!target->is_object()) return c.fail(tp, "is not an object");
    RAYSTER_TRY(c.ref(*target, "node", tp, "nodes"));
    RAYSTER_TRY(c.string(*target, "path", tp, true));
    const std::string path = (*target)["path"].get<std::string>();
    const Json* node = Checker::find(*target, "node");
    if (!node) continue;  // no node: the channel is ignored (or an extension says what it animates)
    const int64_t n = node->get<int64_t>();
    if (!seen.insert({n, path}).second) return c.fail(tp, "node {} {} is animated twice", n, path);
    const Json& nodeJson = c.element("nodes", size_t(n));
    const bool trs = path == "translation" || path == "rotation" || path == "scale";
    if (trs && nodeJson.contains("matrix"))
      return c.fail(tp, "animates the {} of node {}, which has a matrix", path, n);
    size_t components = trs ? (path == "rotation" ? 4 : 3) : 1;
    const char* type = path == "rotation" ? "VEC4" : trs ? "VEC3" : "SCALAR";
    uint64_t perKey = 1;
    if (path == "weights") {
      const Json* mesh = Checker::find(nodeJson, "mesh");
      perKey = mesh ? targets[mesh->get<size_t>()] : 0;
      if (perKey == 0) return c.fail(tp, "animates the weights of node {}, whose mesh has no morph targets", n);
    } else if (!trs) {
      continue;  // an unknown path: only a warning
    }
    const Json& sampler = samplers[channel["sampler"].get<size_t>()];
    const Json& output = c.element("accessors", sampler["output"].get<size_t>());
    if (output["type"] != type)
      return c.fail(cp, "sampler {} output accessor {} is {}, {} needs {}", channel["sampler"].get<uint64_t>(),
                    sampler["output"].get<uint64_t>(), output["type"].get<std::string>(), path, type);
    (void)components;
    const bool cubic = sampler.value("interpolation", "") == "CUBICSPLINE";
    const uint64_t keys = c.element("accessors", sampler["input"].get<size_t>())["count"].get<uint64_t>();
    const uint64_t want = keys * perKey * (cubic ? 3 : 1);
    if (output["count"].get<uint64_t>() != want)
      return c.fail(cp, "sampler {} output accessor {} has {} elements, {} keys of {} need {}",
                    channel["sampler"].get<uint64_t>(), sampler["output"].get<uint64_t>(),
                    output["count"].get<uint64_t>(), keys, path, want);
  }
  return okStatus();
}

Status checkCamera(const Checker& c, size_t i) {
  const Json& cam = c.element("cameras", i);
  const std::string p = fmt::format("cameras[{}]", i);
  RAYSTER_TRY(c.string(cam, "type", p, true));
  const std::string type = cam["type"].get<std::string>();
  const bool persp = cam.contains("perspective"), ortho = cam.contains("orthographic");
  if (persp && ortho) return c.fail(p, "has both perspective and orthographic");
  if (type == "perspective" && !persp) return c.fail(p, "perspective is required for type perspective");
  if (type == "orthographic" && !ortho) return c.fail(p, "orthographic is required for type orthographic");
  if (persp) {
    const Json& v = cam["perspective"];
    const std::string pp = Checker::at(p, "perspective");
    if (!v.is_object()) return c.fail(pp, "is not an object");
    RAYSTER_TRY(c.number(v, "yfov", pp, kPositive, true));
    RAYSTER_TRY(c.number(v, "znear", pp, kPositive, true));
    RAYSTER_TRY(c.number(v, "zfar", pp, kPositive));
    RAYSTER_TRY(c.number(v, "aspectRatio", pp, kPositive));
    if (v.contains("zfar") && !(v["zfar"].get<double>() > v["znear"].get<double>()))
      return c.fail(Checker::at(pp, "zfar"), "{} is not beyond znear {}", v["zfar"].get<double>(),
                    v["znear"].get<double>());
  }
  if (ortho) {
    const Json& v = cam["orthographic"];
    const std::string op = Checker::at(p, "orthographic");
    if (!v.is_object()) return c.fail(op, "is not an object");
    RAYSTER_TRY(c.number(v, "xmag", op, kAny, true));
    RAYSTER_TRY(c.number(v, "ymag", op, kAny, true));
    RAYSTER_TRY(c.number(v, "zfar", op, kPositive, true));
    RAYSTER_TRY(c.number(v, "znear", op, kNonNegative, true));
    for (const char* key : {"xmag", "ymag"})
      if (v[key].get<double>() == 0.0) return c.fail(Checker::at(op, key), "is 0");
    if (!(v["zfar"].get<double>() > v["znear"].get<double>()))
      return c.fail(Checker::at(op, "zfar"), "{} is not beyond znear {}", v["zfar"].get<double>(),
                    v["znear"].get<double>());
  }
  return okStatus();
}

}  // namespace

Status checkSkinsAndAnimations(const Checker& c) {
  std::vector<int64_t> parent;
  RAYSTER_TRY(hierarchy(c, parent));
  RAYSTER_TRY(checkSkins(c, parent));
  const std::vector<size_t> targets = meshTargets(c);
  for (size_t a = 0; a < c.count("animations"); ++a) RAYSTER_TRY(checkAnimation(c, a, targets));
  return okStatus();
}

Status checkCameras(const Checker& c) {
  for (size_t i = 0; i < c.count("cameras"); ++i) RAYSTER_TRY(checkCamera(c, i));
  return okStatus();
}

}  // namespace rayster::scene::gltf::schema
