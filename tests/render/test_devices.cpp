// `--device N|UUID|NAME` and `rayster info [--json]`: one process per GPU needs a way to name
// each GPU of a node whose GPUs share one name.
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/render/run_rayster.h"

namespace rayster::test {
namespace {

nlohmann::json infoJson() {
  RunResult r = runRayster("info --json");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  // The validation layer may add lines on stderr (one pipe here): the array starts at '['.
  const size_t start = r.output.find('[');
  if (start == std::string::npos) return {};
  return nlohmann::json::parse(r.output.substr(start), nullptr, false);
}

TEST(DeviceSelection, InfoListsEachDevicesIndexAndUuid) {
  const nlohmann::json list = infoJson();
  ASSERT_TRUE(list.is_array() && !list.empty()) << list.dump();
  const std::regex uuid("[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}");
  RunResult text = runRayster("info");
  ASSERT_EQ(text.exitCode, 0) << text.output;
  for (size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& d = list[i];
    EXPECT_EQ(d["index"], i);
    const std::string u = d["uuid"];
    EXPECT_TRUE(std::regex_match(u, uuid)) << u;
    EXPECT_TRUE(d["name"].is_string() && d["ray_tracing_pipeline"].is_boolean()) << d.dump();
    EXPECT_NE(text.output.find(std::to_string(i) + ": " + d["name"].get<std::string>()), std::string::npos)
        << text.output;
    EXPECT_NE(text.output.find("UUID " + u), std::string::npos) << text.output;
  }
}

TEST(DeviceSelection, ADeviceIsChosenByIndexUuidOrName) {
  const nlohmann::json list = infoJson();
  ASSERT_TRUE(list.is_array() && !list.empty());
  const std::string name = list[0]["name"], uuid = list[0]["uuid"];
  std::string upperUuid = uuid;
  for (char& c : upperUuid) c = char(std::toupper(static_cast<unsigned char>(c)));
  const auto dir = testDir();
  for (const std::string& device : {std::string("0"), uuid, upperUuid, name.substr(0, 4)}) {
    RunResult r = runRayster("render builtin:cornell --mode raster --size 16x12 --frames 1 -v --device '" + device +
                             "' -o " + (dir / "d.png").string());
    EXPECT_EQ(r.exitCode, 0) << device << "\n" << r.output;
    EXPECT_NE(r.output.find("device: " + name), std::string::npos) << device << "\n" << r.output;
  }
}

TEST(DeviceSelection, ADeviceThatDoesNotExistExitsFourListingTheDevices) {
  const nlohmann::json list = infoJson();
  ASSERT_TRUE(list.is_array() && !list.empty());
  const std::string listed =
      "devices: 0 " + list[0]["name"].get<std::string>() + " " + list[0]["uuid"].get<std::string>();
  const auto dir = testDir();
  for (const std::string device :
       {std::to_string(list.size()), std::string("00000000-0000-0000-0000-000000000000"), std::string("no-such-gpu")}) {
    RunResult r = runRayster("render builtin:cornell --size 16x12 --frames 1 --device " + device + " -o " +
                             (dir / "d.png").string());
    EXPECT_EQ(r.exitCode, 4) << device << "\n" << r.output;
    EXPECT_NE(r.output.find("rayster: error: no Vulkan device has"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(listed), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 2) << "the scene's line and the cause\n" << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "d.png"));
}

}  // namespace
}  // namespace rayster::test
