// glTF meshes -> scene::Mesh: triangle primitives, attributes, indices, generated flat normals.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/log.h"
#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

const char* modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "POINTS";
    case TINYGLTF_MODE_LINE:
      return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
      return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
      return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES:
      return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN:
      return "TRIANGLE_FAN";
    default:
      return "unknown";
  }
}

int attribute(const tinygltf::Primitive& prim, const char* name) {
  auto it = prim.attributes.find(name);
  return it == prim.attributes.end() ? -1 : it->second;
}

// The glTF spec: "When normals are not specified, client implementations MUST calculate flat
// normals". Flat means no vertex is shared between triangles, so the primitive is un-indexed
// first (every triangle gets its own three vertices, with all their attributes).
void generateFlatNormals(Primitive& prim) {
  auto expand = [&](auto& attribute) {
    if (attribute.empty()) return;
    std::remove_reference_t<decltype(attribute)> out;
    out.reserve(prim.indices.size());
    for (uint32_t i : prim.indices) out.push_back(attribute[i]);
    attribute = std::move(out);
  };
  expand(prim.positions);
  expand(prim.tangents);
  expand(prim.uvs);
  expand(prim.uvs1);
  expand(prim.colors);
  for (SkinInfluences& set : prim.influences) expand(set.joints), expand(set.weights);
  for (MorphTarget& target : prim.targets) expand(target.positions), expand(target.normals), expand(target.tangents);
  for (size_t i = 0; i < prim.indices.size(); ++i) prim.indices[i] = uint32_t(i);
  prim.normals.assign(prim.positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  for (size_t t = 0; t + 2 < prim.positions.size(); t += 3) {
    const glm::vec3 n =
        glm::cross(prim.positions[t + 1] - prim.positions[t], prim.positions[t + 2] - prim.positions[t]);
    const float length = glm::length(n);
    // Degenerate triangles cover no pixels; any unit normal keeps the shaders finite.
    const glm::vec3 normal = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
    prim.normals[t] = prim.normals[t + 1] = prim.normals[t + 2] = normal;
  }
}

uint32_t defaultMaterial(MeshBuilder& builder) {
  if (!builder.defaultMaterial) {
    // glTF 2.0 §3.9.2: a primitive without a material uses the default material, whose
    // pbrMetallicRoughness has every default: metallic 1 (scene::Material's own default is a
    // dielectric, as OBJ and the built-in scenes expect), roughness 1, white base colour.
    Material material;
    material.name = "default";
    material.metallic = 1.0f;
    builder.defaultMaterial = uint32_t(builder.scene.materials.size());
    builder.scene.materials.push_back(material);
  }
  return *builder.defaultMaterial;
}

// COLOR_0 as linear RGBA (VEC3: alpha 1). The spec allows float and normalized unsigned byte or
// short; anything else is dropped with a warning (the primitive renders white), since colours are
// decoration, unlike positions or indices. Float values are clamped to [0, 1], NaN to 1.
Result<std::vector<glm::vec4>> readColors(const tinygltf::Model& model, int index, const std::string& file,
                                          const std::string& where) {
  if (index < 0 || size_t(index) >= model.accessors.size())
    return bad(file, "{}: COLOR_0 accessor {} does not exist", where, index);
  const tinygltf::Accessor& acc = model.accessors[size_t(index)];
  const bool normalizedInteger = acc.normalized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                    acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  if ((acc.type != TINYGLTF_TYPE_VEC3 && acc.type != TINYGLTF_TYPE_VEC4) ||
      (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !normalizedInteger)) {
    log::warn("{}: {}: COLOR_0 is not float or normalized unsigned byte/short VEC3/VEC4; vertex colours ignored", file,
              where);
    return std::vector<glm::vec4>{};
  }
  std::vector<glm::vec4> colors;
  if (acc.type == TINYGLTF_TYPE_VEC3) {
    auto rgb = readVec3(model, index, file);
    if (!rgb) return rgb.error();
    colors.reserve(rgb->size());
    for (const glm::vec3& c : *rgb) colors.emplace_back(c, 1.0f);
  } else {
    auto rgba = readVec4(model, index, file);
    if (!rgba) return rgba.error();
    colors = std::move(*rgba);
  }
  for (glm::vec4& c : colors)
    for (int k = 0; k < 4; ++k) c[k] = std::isnan(c[k]) ? 1.0f : std::clamp(c[k], 0.0f, 1.0f);
  return colors;
}

// JOINTS_n with WEIGHTS_n, for n = 0, 1, … as long as both are there (glTF 2.0 §3.7.3.3): joints
// as unsigned byte or short, weights as float or normalized unsigned byte or short, VEC4 each.
Status readSkinInfluences(const tinygltf::Model& model, const tinygltf::Primitive& src, const std::string& file,
                          const std::string& where, Primitive& prim) {
  const size_t vertexCount = prim.positions.size();
  for (int set = 0;; ++set) {
    const int joints = attribute(src, fmt::format("JOINTS_{}", set).c_str());
    const int weights = attribute(src, fmt::format("WEIGHTS_{}", set).c_str());
    if (joints < 0 && weights < 0) break;
    if (joints < 0 || weights < 0)
      return bad(file, "{}: {} without {}", where,
                 joints < 0 ? fmt::format("WEIGHTS_{}", set) : fmt::format("JOINTS_{}", set),
                 joints < 0 ? fmt::format("JOINTS_{}", set) : fmt::format("WEIGHTS_{}", set));
    if (size_t(joints) >= model.accessors.size())
      return bad(file, "{}: JOINTS_{} accessor {} does not exist", where, set, joints);
    const tinygltf::Accessor& ja = model.accessors[size_t(joints)];
    if (ja.type != TINYGLTF_TYPE_VEC4 ||
        (ja.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         ja.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) ||
        ja.normalized)
      return bad(file, "{}: JOINTS_{} must be VEC4 unsigned byte or unsigned short", where, set);
    auto j = readVec4(model, joints, file);
    if (!j) return j.error();
    auto w = readVec4(model, weights, file);
    if (!w) return w.error();
    if (j->size() != vertexCount || w->size() != vertexCount)
      return bad(file, "{}: JOINTS_{}/WEIGHTS_{} have {}/{} elements for {} positions", where, set, set, j->size(),
                 w->size(), vertexCount);
    SkinInfluences influences;
    influences.joints.reserve(vertexCount);
    for (const glm::vec4& v : *j) influences.joints.emplace_back(glm::u16vec4(v));
    influences.weights = std::move(*w);
    for (size_t i = 0; i < vertexCount; ++i)
      for (int k = 0; k < 4; ++k)
        if (!(influences.weights[i][k] >= 0.0f) || !std::isfinite(influences.weights[i][k]))
          return bad(file, "{}: WEIGHTS_{} of vertex {} is {}, not a finite weight >= 0", where, set, i,
                     influences.weights[i][k]);
    prim.influences.push_back(std::move(influences));
  }
  return okStatus();
}

// Morph targets: POSITION, NORMAL and TANGENT displacements (VEC3 each), every one optional.
Status readMorphTargets(const tinygltf::Model& model, const tinygltf::Primitive& src, const std::string& file,
                        const std::string& where, Primitive& prim) {
  const size_t vertexCount = prim.positions.size();
  for (size_t t = 0; t < src.targets.size(); ++t) {
    MorphTarget target;
    for (const auto& [name, accessor] : src.targets[t]) {
      std::vector<glm::vec3>* into = name == "POSITION"  ? &target.positions
                                     : name == "NORMAL"  ? &target.normals
                                     : name == "TANGENT" ? &target.tangents
                                                         : nullptr;
      if (!into) continue;  // TEXCOORD_n and COLOR_n targets are allowed and not morphed here
      auto deltas = readVec3(model, accessor, file);
      if (!deltas) return deltas.error();
      if (deltas->size() != vertexCount)
        return bad(file, "{}: target {} {} has {} elements for {} positions", where, t, name, deltas->size(),
                   vertexCount);
      for (size_t i = 0; i < vertexCount; ++i)
        if (!std::isfinite((*deltas)[i].x + (*deltas)[i].y + (*deltas)[i].z))
          return bad(file, "{}: target {} {} element {} is not finite", where, t, name, i);
      *into = std::move(*deltas);
    }
    prim.targets.push_back(std::move(target));
  }
  return okStatus();
}

// "mesh 'name'" or, for unnamed meshes, "mesh 3".
std::string meshLabel(const tinygltf::Mesh& mesh, int index) {
  return mesh.name.empty() ? fmt::format("mesh {}", index) : fmt::format("mesh '{}'", mesh.name);
}

// POSITION's accessor min and max (required, glTF 2.0 §5.1.1) must bound its data: a file whose
// positions fall outside them contradicts itself (what its bounds say is culled or framed wrongly
// by any viewer that trusts them). Looser bounds are tolerated, and rounding of the bounds to fewer
// digits than the data's (1e-5 of their magnitude).
Status checkBounds(const tinygltf::Accessor& acc, const std::vector<glm::vec3>& positions, const std::string& file,
                   const std::string& what) {
  if (acc.minValues.size() != 3 || acc.maxValues.size() != 3 || positions.empty()) return okStatus();
  for (int c = 0; c < 3; ++c) {
    const double lo = acc.minValues[size_t(c)], hi = acc.maxValues[size_t(c)];
    const double slack = 1e-5 * std::max({1.0, std::abs(lo), std::abs(hi)});
    for (size_t i = 0; i < positions.size(); ++i) {
      const double v = positions[i][c];
      if (v < lo - slack || v > hi + slack)
        return bad(file, "{}: position {} has {} = {}, outside the accessor's min {} and max {}", what, i, "xyz"[c], v,
                   lo, hi);
    }
  }
  return okStatus();
}

// A triangle strip's or fan's vertex order as a triangle list, with glTF 2.0's winding (§3.7.2.1):
// strip triangle i is {v_i, v_{i+1+i%2}, v_{i+2-i%2}}, fan triangle i is {v_{i+1}, v_{i+2}, v_0}.
std::vector<uint32_t> triangulate(const std::vector<uint32_t>& v, bool strip) {
  std::vector<uint32_t> out;
  if (v.size() < 3) return out;
  out.reserve((v.size() - 2) * 3);
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    if (strip)
      out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
    else
      out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
  }
  return out;
}

Result<Primitive> convertPrimitive(MeshBuilder& builder, const tinygltf::Mesh& mesh, int meshIndex, size_t primIndex) {
  const tinygltf::Primitive& src = mesh.primitives[primIndex];
  const std::string& file = builder.file;
  const tinygltf::Model& model = builder.model;
  const std::string label = meshLabel(mesh, meshIndex);
  // tinygltf reports an absent mode as -1 in some versions and 4 in others; both mean triangles.
  // Strips and fans become triangle lists (triangulate() below).
  const bool strip = src.mode == TINYGLTF_MODE_TRIANGLE_STRIP, fan = src.mode == TINYGLTF_MODE_TRIANGLE_FAN;
  if (src.mode != TINYGLTF_MODE_TRIANGLES && src.mode != -1 && !strip && !fan)
    return bad(file, "{} primitive {} uses mode {}, which glTF does not define", label, primIndex, src.mode);

  Primitive prim;
  auto positions = readVec3(model, attribute(src, "POSITION"), file);  // convertMesh checked it is there
  if (!positions) return positions.error();
  prim.positions = std::move(*positions);
  RAYSTER_TRY(checkBounds(model.accessors[size_t(attribute(src, "POSITION"))], prim.positions, file,
                          fmt::format("{} primitive {}", label, primIndex)));
  const size_t vertexCount = prim.positions.size();
  if (vertexCount > UINT32_MAX) return bad(file, "{} primitive {} has too many vertices", label, primIndex);

  // Optional attributes must match POSITION's count; a mismatch is a broken file, not a detail.
  auto checkCount = [&](size_t count, const char* what) -> Status {
    if (count != vertexCount)
      return bad(file, "{} primitive {}: {} has {} elements for {} positions", label, primIndex, what, count,
                 vertexCount);
    return okStatus();
  };
  if (int a = attribute(src, "NORMAL"); a >= 0) {
    auto normals = readVec3(model, a, file);
    if (!normals) return normals.error();
    RAYSTER_TRY(checkCount(normals->size(), "NORMAL"));
    prim.normals = std::move(*normals);
  }
  if (int a = attribute(src, "TANGENT"); a >= 0) {
    auto tangents = readVec4(model, a, file);
    if (!tangents) return tangents.error();
    RAYSTER_TRY(checkCount(tangents->size(), "TANGENT"));
    prim.tangents = std::move(*tangents);
  }
  if (int a = attribute(src, "TEXCOORD_0"); a >= 0) {
    auto uvs = readVec2(model, a, file);
    if (!uvs) return uvs.error();
    RAYSTER_TRY(checkCount(uvs->size(), "TEXCOORD_0"));
    prim.uvs = std::move(*uvs);
  }
  if (int a = attribute(src, "TEXCOORD_1"); a >= 0) {
    auto uvs = readVec2(model, a, file);
    if (!uvs) return uvs.error();
    RAYSTER_TRY(checkCount(uvs->size(), "TEXCOORD_1"));
    prim.uvs1 = std::move(*uvs);
  }

  if (int a = attribute(src, "COLOR_0"); a >= 0) {
    auto colors = readColors(model, a, file, fmt::format("{} primitive {}", label, primIndex));
    if (!colors) return colors.error();
    if (!colors->empty()) RAYSTER_TRY(checkCount(colors->size(), "COLOR_0"));
    prim.colors = std::move(*colors);
  }

  RAYSTER_TRY(readSkinInfluences(model, src, file, fmt::format("{} primitive {}", label, primIndex), prim));
  RAYSTER_TRY(readMorphTargets(model, src, file, fmt::format("{} primitive {}", label, primIndex), prim));

  if (src.indices >= 0) {
    auto indices = readIndices(model, src.indices, file);
    if (!indices) return indices.error();
    prim.indices = std::move(*indices);
    for (size_t i = 0; i < prim.indices.size(); ++i)
      if (prim.indices[i] >= vertexCount)
        return bad(file, "{} primitive {}: index {} is {}, past the vertex count {}", label, primIndex, i,
                   prim.indices[i], vertexCount);
  } else {
    prim.indices.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) prim.indices[i] = uint32_t(i);
  }
  if (strip || fan) prim.indices = triangulate(prim.indices, strip);
  // A count that is no multiple of 3 is only a warning in the glTF-Validator
  // (MESH_PRIMITIVE_INCOMPATIBLE_MODE): the whole triangles are drawn, the rest left out.
  if (prim.indices.size() % 3 != 0) {
    log::warn("{}: {} primitive {}: {} indices is not a whole number of triangles; the last {} left out", file, label,
              primIndex, prim.indices.size(), prim.indices.size() % 3);
    prim.indices.resize(prim.indices.size() / 3 * 3);
  }
  for (size_t i = 0; i < vertexCount; ++i)
    if (!std::isfinite(prim.positions[i].x) || !std::isfinite(prim.positions[i].y) ||
        !std::isfinite(prim.positions[i].z))
      return bad(file, "{} primitive {}: position {} is not finite", label, primIndex, i);

  if (prim.normals.empty()) generateFlatNormals(prim);

  if (src.material >= 0) {
    if (size_t(src.material) >= model.materials.size())
      return bad(file, "{} primitive {} uses material {}, which does not exist", label, primIndex, src.material);
    prim.material = uint32_t(src.material);  // materials are converted in glTF order, so indices carry over
  } else {
    prim.material = defaultMaterial(builder);
  }
  RAYSTER_TRY(readVariantMappings(src, builder.scene, model.materials.size(), file,
                                  fmt::format("meshes[{}].primitives[{}]", meshIndex, primIndex), prim));
  return prim;
}

}  // namespace

Result<Mesh> convertMesh(MeshBuilder& builder, int meshIndex) {
  const tinygltf::Mesh& src = builder.model.meshes[size_t(meshIndex)];
  Mesh mesh;
  mesh.name = src.name.empty() ? fmt::format("mesh{}", meshIndex) : src.name;
  for (size_t p = 0; p < src.primitives.size(); ++p) {
    // POSITION is optional in glTF 2.0; without it "client implementations SHOULD skip primitive's
    // rendering" (the spec), so the file is valid and only this primitive is left out.
    if (attribute(src.primitives[p], "POSITION") < 0) {
      log::warn("{}: {} primitive {} has no POSITION attribute; skipped", builder.file, meshLabel(src, meshIndex), p);
      continue;
    }
    // Points and lines are valid glTF with no surface to shade or trace: left out, said once each.
    const int mode = src.primitives[p].mode;
    if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
        mode == TINYGLTF_MODE_LINE_STRIP) {
      log::warn("{}: {} primitive {} is drawn as {}; Rayster draws surfaces only, skipped", builder.file,
                meshLabel(src, meshIndex), p, modeName(mode));
      continue;
    }
    Result<Primitive> prim = convertPrimitive(builder, src, meshIndex, p);
    if (!prim) return prim.error();
    // A primitive without triangles adds nothing to draw and would be an empty BLAS geometry.
    if (prim->indices.empty()) continue;
    mesh.primitives.push_back(std::move(*prim));
  }
  // Every primitive has as many targets as the mesh has weights (glTF 2.0 §3.7.2.2).
  size_t targets = src.primitives.empty() ? 0 : src.primitives.front().targets.size();
  for (size_t p = 0; p < src.primitives.size(); ++p)
    if (src.primitives[p].targets.size() != targets)
      return bad(builder.file, "{}: primitive {} has {} morph targets, primitive 0 has {}", meshLabel(src, meshIndex),
                 p, src.primitives[p].targets.size(), targets);
  if (!src.weights.empty() && src.weights.size() != targets)
    return bad(builder.file, "{}: {} weights for {} morph targets", meshLabel(src, meshIndex), src.weights.size(),
               targets);
  for (double w : src.weights) {
    if (!std::isfinite(w)) return bad(builder.file, "{}: a morph weight is not finite", meshLabel(src, meshIndex));
    mesh.weights.push_back(float(w));
  }
  return mesh;
}

}  // namespace rayster::scene::gltf
