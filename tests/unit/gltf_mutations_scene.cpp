// The second half of the glTF mutations (gltf_mutations.h): nodes, scenes, cameras, lights,
// materials, images, samplers, skins and animations.
#include <cmath>

#include "gltf_mutations.h"

namespace rayster::test::mutation {

std::vector<Mutation> sceneMutations() {
  const double halfPi = std::acos(0.0);
  return {
      // nodes
      {"matrix with 15 numbers", [](Doc& d) { d.node(0)["matrix"] = Json(std::vector<double>(15, 0.0)); },
       "nodes[0].matrix"},
      {"matrix with 17 numbers", [](Doc& d) { d.node(0)["matrix"] = Json(std::vector<double>(17, 0.0)); },
       "nodes[0].matrix"},
      {"translation with 2 numbers",
       [](Doc& d) {
         d.node(0)["translation"] = {1, 2};
       },
       "nodes[0].translation"},
      {"scale with 4 numbers",
       [](Doc& d) {
         d.node(0)["scale"] = {1, 1, 1, 1};
       },
       "nodes[0].scale"},
      {"rotation of length 0.9",
       [](Doc& d) {
         d.node(0)["rotation"] = {0, 0, 0, 0.9};
       },
       "nodes[0].rotation"},
      {"rotation of length 0.99",
       [](Doc& d) {
         d.node(0)["rotation"] = {0, 0, 0, 0.99};
       },
       "nodes[0].rotation"},
      {"rotation within the tolerance",
       [](Doc& d) {
         d.node(0)["rotation"] = {0, 0, 0, 0.995};
       },
       nullptr},
      {"rotation component above 1",
       [](Doc& d) {
         d.node(0)["rotation"] = {0, 0, 0, 1.001};
       },
       "nodes[0].rotation[3]"},
      {"matrix and scale",
       [](Doc& d) {
         d.node(0)["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
         d.node(0)["scale"] = {1, 1, 1};
       },
       "nodes[0]"},
      {"a projective matrix", [](Doc& d) { d.node(0)["matrix"] = {1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
       "nodes[0].matrix"},
      {"a matrix of scale 0", [](Doc& d) { d.node(0)["matrix"] = {0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
       "nodes[0].matrix"},
      {"a sheared matrix", [](Doc& d) { d.node(0)["matrix"] = {1, 0, 0, 0, 0.01, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
       "nodes[0].matrix"},
      {"a matrix with a shear of 1e-4",
       [](Doc& d) { d.node(0)["matrix"] = {1, 0, 0, 0, 0.0001, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }, nullptr},
      {"a mirroring, rotating and scaling matrix",
       [](Doc& d) { d.node(0)["matrix"] = {0, -3, 0, 0, 2, 0, 0, 0, 0, 0, -1, 0, 5, 6, 7, 1}; }, nullptr},
      {"a translating matrix", [](Doc& d) { d.node(0)["matrix"] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1}; },
       nullptr},
      {"node mesh out of range", [](Doc& d) { d.node(0)["mesh"] = 5; }, "nodes[0].mesh"},
      {"node camera out of range", [](Doc& d) { d.node(0)["camera"] = 2; }, "nodes[0].camera"},
      {"a node that is its own child", [](Doc& d) { d.node(0)["children"] = {0}; }, "nodes[0].children[0]"},
      {"a cycle of children",
       [](Doc& d) {
         d.j["nodes"].push_back({{"children", {2}}});
         d.j["nodes"].push_back({{"children", {1}}});
       },
       "nodes[1]"},
      {"a node with two parents",
       [](Doc& d) {
         d.j["nodes"].push_back({{"children", {3}}});
         d.j["nodes"].push_back({{"children", {3}}});
         d.j["nodes"].push_back(Json::object());
       },
       "nodes[2].children[0]"},
      {"children empty", [](Doc& d) { d.node(0)["children"] = Json::array(); }, "nodes[0].children"},
      {"a child listed twice",
       [](Doc& d) {
         d.j["nodes"].push_back(Json::object());
         d.node(0)["children"] = {1, 1};
       },
       "nodes[0].children[1]"},
      {"a scene listing a child",
       [](Doc& d) {
         d.j["nodes"].push_back(Json::object());
         d.node(0)["children"] = {1};
         d.j["scenes"][0]["nodes"].push_back(1);
       },
       "scenes[0].nodes[1]"},
      {"scene nodes empty", [](Doc& d) { d.j["scenes"][0]["nodes"] = Json::array(); }, "scenes[0].nodes"},
      {"scene node out of range", [](Doc& d) { d.j["scenes"][0]["nodes"] = {7}; }, "scenes[0].nodes[0]"},
      {"another scene without nodes", [](Doc& d) { d.j["scenes"].push_back(Json::object()); }, nullptr},
      {"a node with no mesh",
       [](Doc& d) {
         addNode(d, {{"name", "empty"}});
       },
       nullptr},
      {"node weights without morph targets", [](Doc& d) { d.node(0)["weights"] = {1.0}; }, "nodes[0].weights"},
      // cameras
      {"a perspective camera",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 0.1}}));
       },
       nullptr},
      {"a perspective camera with zfar and aspect ratio",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 100}, {"aspectRatio", 1.5}}));
       },
       nullptr},
      {"yfov above pi",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 4.0}, {"znear", 0.1}}));
       },
       nullptr},
      {"yfov 0",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.0}, {"znear", 0.1}}));
       },
       "cameras[0].perspective.yfov"},
      {"znear 0",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 0.0}}));
       },
       "cameras[0].perspective.znear"},
      {"zfar before znear",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 1.0}, {"zfar", 0.5}}));
       },
       "cameras[0].perspective.zfar"},
      {"aspectRatio 0",
       [](Doc& d) {
         camera(d, perspective({{"yfov", 0.8}, {"znear", 0.1}, {"aspectRatio", 0}}));
       },
       "cameras[0].perspective.aspectRatio"},
      {"perspective camera without perspective",
       [](Doc& d) {
         camera(d, {{"type", "perspective"}});
       },
       "cameras[0]"},
      {"a camera both perspective and orthographic",
       [](Doc& d) {
         Json c = perspective({{"yfov", 0.8}, {"znear", 0.1}});
         c["orthographic"] = {{"xmag", 1}, {"ymag", 1}, {"znear", 0}, {"zfar", 1}};
         camera(d, c);
       },
       "cameras[0]"},
      {"an unknown camera type",
       [](Doc& d) {
         Json c = perspective({{"yfov", 0.8}, {"znear", 0.1}});
         c["type"] = "fisheye";
         camera(d, c);
       },
       nullptr},
      {"an orthographic camera",
       [](Doc& d) {
         camera(d, orthographic({{"xmag", 1}, {"ymag", 1}, {"znear", 0}, {"zfar", 10}}));
       },
       nullptr},
      {"orthographic xmag 0",
       [](Doc& d) {
         camera(d, orthographic({{"xmag", 0}, {"ymag", 1}, {"znear", 0}, {"zfar", 10}}));
       },
       "cameras[0].orthographic.xmag"},
      {"orthographic znear -1",
       [](Doc& d) {
         camera(d, orthographic({{"xmag", 1}, {"ymag", 1}, {"znear", -1}, {"zfar", 10}}));
       },
       "cameras[0].orthographic.znear"},
      {"orthographic zfar at znear",
       [](Doc& d) {
         camera(d, orthographic({{"xmag", 1}, {"ymag", 1}, {"znear", 2}, {"zfar", 2}}));
       },
       "cameras[0].orthographic.zfar"},
      // KHR_lights_punctual
      {"a spot light",
       [&](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.0}, {"outerConeAngle", halfPi}}}});
       },
       nullptr},
      {"a light type glTF does not define",
       [](Doc& d) {
         light(d, {{"type", "area"}});
       },
       nullptr},
      {"light not in extensionsUsed",
       [](Doc& d) {
         light(d, {{"type", "point"}});
         d.j.erase("extensionsUsed");
       },
       nullptr},
      {"light without type", [](Doc& d) { light(d, Json::object()); }, "extensions.KHR_lights_punctual.lights[0]"},
      {"negative intensity",
       [](Doc& d) {
         light(d, {{"type", "point"}, {"intensity", -1}});
       },
       "KHR_lights_punctual.lights[0].intensity"},
      {"range 0",
       [](Doc& d) {
         light(d, {{"type", "point"}, {"range", 0}});
       },
       "KHR_lights_punctual.lights[0].range"},
      {"light colour above 1",
       [](Doc& d) {
         light(d, {{"type", "point"}, {"color", {2, 0, 0}}});
       },
       "KHR_lights_punctual.lights[0].color[0]"},
      {"spot outer below inner",
       [](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.4}}}});
       },
       "lights[0].spot.outerConeAngle"},
      {"spot outer equal to inner",
       [](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.4}, {"outerConeAngle", 0.4}}}});
       },
       "lights[0].spot.outerConeAngle"},
      {"spot outer above pi/2",
       [](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}});
       },
       "lights[0].spot.outerConeAngle"},
      {"spot inner negative",
       [](Doc& d) {
         light(d, {{"type", "spot"}, {"spot", {{"innerConeAngle", -0.1}}}});
       },
       "lights[0].spot.innerConeAngle"},
      {"spot light without spot",
       [](Doc& d) {
         light(d, {{"type", "spot"}});
       },
       "lights[0]"},
      {"node light out of range",
       [](Doc& d) {
         light(d, {{"type", "point"}});
         d.j["nodes"].back()["extensions"]["KHR_lights_punctual"]["light"] = 3;
       },
       "extensions.KHR_lights_punctual.light"},
      // materials
      {"a material with factors at their limits",
       [](Doc& d) {
         material(d, {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0}}, {"metallicFactor", 0}}},
                      {"emissiveFactor", {1, 1, 1}},
                      {"alphaMode", "MASK"},
                      {"alphaCutoff", 0}});
       },
       nullptr},
      {"metallicFactor 2",
       [](Doc& d) {
         pbr(d, {{"metallicFactor", 2}});
       },
       "materials[0].pbrMetallicRoughness.metallicFactor"},
      {"roughnessFactor -0.1",
       [](Doc& d) {
         pbr(d, {{"roughnessFactor", -0.1}});
       },
       "materials[0].pbrMetallicRoughness.roughnessFactor"},
      {"baseColorFactor with 3 numbers",
       [](Doc& d) {
         pbr(d, {{"baseColorFactor", {1, 1, 1}}});
       },
       "materials[0].pbrMetallicRoughness.baseColorFactor"},
      {"baseColorFactor 1.5",
       [](Doc& d) {
         pbr(d, {{"baseColorFactor", {1.5, 1, 1, 1}}});
       },
       "materials[0].pbrMetallicRoughness.baseColorFactor[0]"},
      {"emissiveFactor 2",
       [](Doc& d) {
         material(d, {{"emissiveFactor", {2, 0, 0}}});
       },
       "materials[0].emissiveFactor[0]"},
      {"alphaCutoff -1",
       [](Doc& d) {
         material(d, {{"alphaMode", "MASK"}, {"alphaCutoff", -1}});
       },
       "materials[0].alphaCutoff"},
      {"an alphaMode glTF does not define",
       [](Doc& d) {
         material(d, {{"alphaMode", "DITHER"}});
       },
       nullptr},
      {"a texture index out of range",
       [](Doc& d) {
         material(d, {{"emissiveTexture", {{"index", 4}}}});
       },
       "materials[0].emissiveTexture.index"},
      {"a texture without index",
       [](Doc& d) {
         material(d, {{"emissiveTexture", Json::object()}});
       },
       "materials[0].emissiveTexture"},
      {"texCoord -1",
       [](Doc& d) {
         material(d, {{"emissiveTexture", {{"index", 0}, {"texCoord", -1}}}});
       },
       "materials[0].emissiveTexture.texCoord"},
      {"occlusion strength 2",
       [](Doc& d) {
         material(d, {{"occlusionTexture", {{"index", 0}, {"strength", 2}}}});
       },
       "materials[0].occlusionTexture.strength"},
      {"a texture without source",
       [](Doc& d) {
         material(d, {{"emissiveTexture", {{"index", 0}}}});
       },
       nullptr},
      {"emissiveStrength -1",
       [](Doc& d) {
         ext(d, "KHR_materials_emissive_strength", {{"emissiveStrength", -1}});
         d.j["materials"][0]["emissiveFactor"] = {1, 1, 1};
       },
       "KHR_materials_emissive_strength.emissiveStrength"},
      {"ior 0.5",
       [](Doc& d) {
         ext(d, "KHR_materials_ior", {{"ior", 0.5}});
       },
       "KHR_materials_ior.ior"},
      {"ior 0",
       [](Doc& d) {
         ext(d, "KHR_materials_ior", {{"ior", 0}});
       },
       nullptr},
      {"transmissionFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_transmission", {{"transmissionFactor", 2}});
       },
       "KHR_materials_transmission.transmissionFactor"},
      {"volume thickness -1",
       [](Doc& d) {
         material(
             d,
             {{"extensions",
               {{"KHR_materials_transmission", Json::object()}, {"KHR_materials_volume", {{"thicknessFactor", -1}}}}}});
       },
       "KHR_materials_volume.thicknessFactor"},
      {"volume attenuationDistance 0",
       [](Doc& d) {
         material(d, {{"extensions",
                       {{"KHR_materials_transmission", Json::object()},
                        {"KHR_materials_volume", {{"attenuationDistance", 0}}}}}});
       },
       "KHR_materials_volume.attenuationDistance"},
      {"volume attenuationColor 2",
       [](Doc& d) {
         material(d, {{"extensions",
                       {{"KHR_materials_transmission", Json::object()},
                        {"KHR_materials_volume", {{"attenuationColor", {2, 1, 1}}}}}}});
       },
       "KHR_materials_volume.attenuationColor[0]"},
      {"specularFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_specular", {{"specularFactor", 2}});
       },
       "KHR_materials_specular.specularFactor"},
      {"specularColorFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_specular", {{"specularColorFactor", {2, 1, 1}}});
       },
       nullptr},
      {"clearcoatFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_clearcoat", {{"clearcoatFactor", 2}});
       },
       "KHR_materials_clearcoat.clearcoatFactor"},
      {"sheenRoughnessFactor 2",
       [](Doc& d) {
         ext(d, "KHR_materials_sheen", {{"sheenRoughnessFactor", 2}});
       },
       "KHR_materials_sheen.sheenRoughnessFactor"},
      {"iridescenceIor 0.5",
       [](Doc& d) {
         ext(d, "KHR_materials_iridescence", {{"iridescenceIor", 0.5}});
       },
       "KHR_materials_iridescence.iridescenceIor"},
      {"anisotropyStrength 2",
       [](Doc& d) {
         ext(d, "KHR_materials_anisotropy", {{"anisotropyStrength", 2}});
       },
       "KHR_materials_anisotropy.anisotropyStrength"},
      {"an extension texture out of range",
       [](Doc& d) {
         ext(d, "KHR_materials_specular", {{"specularTexture", {{"index", 3}}}});
       },
       "KHR_materials_specular.specularTexture.index"},
      {"texture transform scale with 1 number",
       [](Doc& d) {
         material(d,
                  {{"emissiveTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {2}}}}}}}}});
         use(d, "KHR_texture_transform");
       },
       "KHR_texture_transform.scale"},
      // images, samplers, textures
      {"an image with uri and bufferView",
       [](Doc& d) {
         d.j["images"] = Json::array(
             {{{"uri", "a.png"}, {"bufferView", d.view(std::vector<uint8_t>(16, 7))}, {"mimeType", "image/png"}}});
       },
       "images[0]"},
      {"an image with neither uri nor bufferView", [](Doc& d) { d.j["images"] = Json::array({Json::object()}); },
       "images[0]"},
      {"an image bufferView without mimeType",
       [](Doc& d) {
         d.j["images"] = Json::array({{{"bufferView", d.view(std::vector<uint8_t>(16, 7))}}});
       },
       "images[0].bufferView"},
      {"an image in a bufferView with byteStride",
       [](Doc& d) {
         d.j["images"] =
             Json::array({{{"bufferView", d.view(std::vector<uint8_t>(16, 7), 4)}, {"mimeType", "image/png"}}});
       },
       "images[0].bufferView"},
      {"an unused image in a bufferView",
       [](Doc& d) {
         d.j["images"] =
             Json::array({{{"bufferView", d.view(std::vector<uint8_t>(16, 7))}, {"mimeType", "image/png"}}});
       },
       nullptr},
      {"texture source out of range",
       [](Doc& d) {
         d.j["textures"] = Json::array({{{"source", 3}}});
       },
       "textures[0].source"},
      {"texture sampler out of range",
       [](Doc& d) {
         d.j["textures"] = Json::array({{{"sampler", 3}}});
       },
       "textures[0].sampler"},
      {"sampler wrapS 12345",
       [](Doc& d) {
         d.j["samplers"] = Json::array({{{"wrapS", 12345}}});
         d.j["textures"] = Json::array({{{"sampler", 0}}});
       },
       nullptr},
      {"sampler magFilter 9984",
       [](Doc& d) {
         d.j["samplers"] = Json::array({{{"magFilter", 9984}}});
         d.j["textures"] = Json::array({{{"sampler", 0}}});
       },
       nullptr},
      // skins
      {"a skin", [](Doc& d) { skin(d); }, nullptr},
      {"a skin with inverse bind matrices", [](Doc& d) { skin(d)["inverseBindMatrices"] = identityMatrices(d, 1); },
       nullptr},
      {"skin joints empty", [](Doc& d) { skin(d)["joints"] = Json::array(); }, "skins[0].joints"},
      {"skin joint out of range", [](Doc& d) { skin(d)["joints"] = {9}; }, "skins[0].joints[0]"},
      {"inverse bind matrices of type VEC4",
       [](Doc& d) { skin(d)["inverseBindMatrices"] = d.floats(std::vector<float>(4, 1.0f), "VEC4", 4); },
       "skins[0].inverseBindMatrices"},
      {"fewer inverse bind matrices than joints",
       [](Doc& d) {
         Json& s = skin(d);
         d.j["nodes"][1]["children"] = {2};
         d.j["nodes"].push_back({{"name", "joint2"}});
         s["joints"] = {1, 2};
         s["inverseBindMatrices"] = identityMatrices(d, 1);
       },
       "skins[0].inverseBindMatrices"},
      {"joints without a common root",
       [](Doc& d) {
         Json& s = skin(d);
         const size_t other = addNode(d, {{"name", "joint2"}});
         s["joints"] = {1, other};
       },
       "skins[0].joints[1]"},
      {"a skeleton that is no ancestor", [](Doc& d) { skin(d)["skeleton"] = 0; }, "skins[0].skeleton"},
      {"a skin on a node without mesh",
       [](Doc& d) {
         skin(d);
         addNode(d, {{"skin", 0}});
       },
       "nodes[2].skin"},
      {"a skin on a mesh without joints",
       [](Doc& d) {
         const size_t joint = addNode(d, {{"name", "joint"}});
         d.j["skins"] = Json::array({{{"joints", {joint}}}});
         d.node(0)["skin"] = 0;
       },
       "nodes[0].skin"},
      // animations
      {"an animation", [](Doc& d) { animate(d); }, nullptr},
      {"a STEP animation", [](Doc& d) { animate(d)["samplers"][0]["interpolation"] = "STEP"; }, nullptr},
      {"an interpolation glTF does not define", [](Doc& d) { animate(d)["samplers"][0]["interpolation"] = "SMOOTH"; },
       nullptr},
      {"a channel without node", [](Doc& d) { animate(d)["channels"][0]["target"].erase("node"); }, nullptr},
      {"an animation without channels", [](Doc& d) { animate(d).erase("channels"); }, "animations[0]"},
      {"a channel sampler out of range", [](Doc& d) { animate(d)["channels"][0]["sampler"] = 3; },
       "animations[0].channels[0].sampler"},
      {"a sampler input out of range", [](Doc& d) { animate(d)["samplers"][0]["input"] = 30; },
       "animations[0].samplers[0].input"},
      {"key times of type VEC3",
       [](Doc& d) {
         animate(d)["samplers"][0]["input"] = d.floats({0, 0, 0, 1, 1, 1}, "VEC3", 3);
       },
       "animations[0].samplers[0].input"},
      {"key times without min/max",
       [](Doc& d) {
         animate(d)["samplers"][0]["input"] = d.floats({0, 1}, "SCALAR", 1);
       },
       nullptr},
      {"an output of the wrong count",
       [](Doc& d) {
         animate(d)["samplers"][0]["output"] = d.floats({0, 0, 0, 1, 0, 0, 2, 0, 0}, "VEC3", 3);
       },
       "animations[0].channels[0]"},
      {"an output of the wrong type",
       [](Doc& d) {
         animate(d)["samplers"][0]["output"] = d.floats({0, 0, 0, 1, 0, 0, 2, 0}, "VEC4", 4);
       },
       "animations[0].channels[0]"},
      {"animating a node with a matrix",
       [](Doc& d) {
         animate(d);
         d.node(0)["matrix"] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1};
       },
       "animations[0].channels[0].target"},
      {"animating weights without morph targets",
       [](Doc& d) {
         Json& a = animate(d);
         a["samplers"][0]["output"] = d.floats({0, 1}, "SCALAR", 1);
         a["channels"][0]["target"]["path"] = "weights";
       },
       "animations[0].channels[0].target"},
      {"the same target twice",
       [](Doc& d) {
         Json& a = animate(d);
         a["channels"].push_back(a["channels"][0]);
       },
       "animations[0].channels[1].target"},
      {"key times not increasing",
       [](Doc& d) {
         animate(d)["samplers"][0]["input"] = times(d, {1, 0.5f});
       },
       "animations[0].samplers[0].input"},
      {"a negative key time",
       [](Doc& d) {
         animate(d)["samplers"][0]["input"] = times(d, {-1, 1});
       },
       "animations[0].samplers[0].input"},
      {"a rotation key of length 0.9",
       [](Doc& d) {
         Json& a = animate(d);
         a["samplers"][0]["output"] = d.floats({0, 0, 0, 1, 0, 0, 0, 0.9f}, "VEC4", 4);
         a["channels"][0]["target"]["path"] = "rotation";
       },
       "animations[0].samplers[0].output"},
      {"a rotation key within the tolerance",
       [](Doc& d) {
         Json& a = animate(d);
         a["samplers"][0]["output"] = d.floats({0, 0, 0, 1, 0, 0, 0, 0.995f}, "VEC4", 4);
         a["channels"][0]["target"]["path"] = "rotation";
       },
       nullptr},
      {"CUBICSPLINE with one key",
       [](Doc& d) {
         Json& a = animate(d);
         a["samplers"][0] = {{"input", times(d, {0})},
                             {"output", d.floats({0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3)},
                             {"interpolation", "CUBICSPLINE"}};
       },
       "animations[0].samplers[0].input"},
  };
}

}  // namespace rayster::test::mutation
