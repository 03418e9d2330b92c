// RenderGraph planning (culling, ordering, barrier derivation) without a GPU: a graph built with a
// null context never calls Vulkan until execute(), so compile() is tested on transient images.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graph/graph.h"

namespace rayster::graph {
namespace {

constexpr VkPipelineStageFlags2 kCs = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kRt = VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR;
constexpr VkPipelineStageFlags2 kFs = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
constexpr VkAccessFlags2 kSw = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
constexpr VkAccessFlags2 kSr = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
constexpr VkAccessFlags2 kSampled = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;

rhi::ImageDesc storageDesc() {
  rhi::ImageDesc d;
  d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  d.width = 64;
  d.height = 32;
  d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  return d;
}

// Adds a pass whose execute callback must never run during planning.
void addPass(RenderGraph& graph, const std::string& name, const std::function<void(PassBuilder&)>& setup) {
  graph.addPass(name, setup, [](PassContext&) { FAIL() << "execute callback ran during compile()"; });
}

std::vector<std::string> passNames(const RenderGraph& graph, const std::vector<PlannedPass>& plan) {
  std::vector<std::string> names;
  for (const PlannedPass& p : plan) names.push_back(graph.passName(p.pass));
  return names;
}

TEST(RenderGraph, CullsUnreadPassAndTheChainFeedingIt) {
  RenderGraph graph(nullptr, nullptr);
  ImageHandle a = graph.createImage("a", storageDesc());
  ImageHandle b = graph.createImage("b", storageDesc());
  ImageHandle kept = graph.createImage("kept", storageDesc());
  addPass(graph, "produceA", [&](PassBuilder& p) { p.write(a, Use::StorageWriteCompute); });
  addPass(graph, "aToB", [&](PassBuilder& p) {
    p.read(a, Use::SampledCompute);
    p.write(b, Use::StorageWriteCompute);
  });
  // Nobody reads b and nothing here has a side effect: produceA and aToB are dead.
  addPass(graph, "produceKept", [&](PassBuilder& p) { p.write(kept, Use::StorageWriteRayTracing); });
  addPass(graph, "readback", [&](PassBuilder& p) {
    p.read(kept, Use::SampledCompute);
    p.sideEffect();
  });
  // A reader without a side effect and without outputs is dead too.
  addPass(graph, "deadReader", [&](PassBuilder& p) { p.read(kept, Use::SampledFragment); });

  const std::vector<PlannedPass> plan = graph.compile();
  EXPECT_EQ(passNames(graph, plan), (std::vector<std::string>{"produceKept", "readback"}));
}

TEST(RenderGraph, SideEffectKeepsPassAndItsProducers) {
  RenderGraph graph(nullptr, nullptr);
  ImageHandle a = graph.createImage("a", storageDesc());
  ImageHandle b = graph.createImage("b", storageDesc());
  addPass(graph, "produceA", [&](PassBuilder& p) { p.write(a, Use::StorageWriteCompute); });
  addPass(graph, "aToB", [&](PassBuilder& p) {
    p.read(a, Use::SampledCompute);
    p.write(b, Use::StorageWriteCompute);
    p.sideEffect();
  });
  const std::vector<PlannedPass> plan = graph.compile();
  EXPECT_EQ(passNames(graph, plan), (std::vector<std::string>{"produceA", "aToB"}));
}

TEST(RenderGraph, ComputeWriteThenRaygenSampleGetsOneBarrier) {
  RenderGraph graph(nullptr, nullptr);
  ImageHandle img = graph.createImage("img", storageDesc());
  addPass(graph, "write", [&](PassBuilder& p) { p.write(img, Use::StorageWriteCompute); });
  addPass(graph, "trace", [&](PassBuilder& p) {
    p.read(img, Use::SampledRayTracing);
    p.sideEffect();
  });
  const std::vector<PlannedPass> plan = graph.compile();
  ASSERT_EQ(plan.size(), 2u);
  ASSERT_EQ(graph.passName(plan[1].pass), "trace");
  ASSERT_EQ(plan[1].barriers.size(), 1u);
  const PlannedBarrier& pb = plan[1].barriers[0];
  EXPECT_TRUE(pb.isImage);
  EXPECT_EQ(pb.resource, img.id);
  EXPECT_EQ(pb.barrier.oldLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(pb.barrier.newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(pb.barrier.srcStages, kCs);
  EXPECT_EQ(pb.barrier.srcAccess, kSw);
  EXPECT_EQ(pb.barrier.dstStages, kRt);
  EXPECT_EQ(pb.barrier.dstAccess, kSampled);
}

TEST(RenderGraph, LivePassesKeepInsertionOrder) {
  RenderGraph graph(nullptr, nullptr);
  ImageHandle x = graph.createImage("x", storageDesc());
  ImageHandle y = graph.createImage("y", storageDesc());
  ImageHandle z = graph.createImage("z", storageDesc());
  addPass(graph, "p0", [&](PassBuilder& p) { p.write(x, Use::StorageWriteCompute); });
  addPass(graph, "p1", [&](PassBuilder& p) { p.write(y, Use::StorageWriteRayTracing); });
  addPass(graph, "dead", [&](PassBuilder& p) { p.write(z, Use::StorageWriteCompute); });
  addPass(graph, "p2", [&](PassBuilder& p) {
    p.read(y, Use::SampledCompute);
    p.read(x, Use::SampledCompute);
    p.sideEffect();
  });
  addPass(graph, "p3", [&](PassBuilder& p) {
    p.read(x, Use::SampledFragment);
    p.sideEffect();
  });
  const std::vector<PlannedPass> plan = graph.compile();
  EXPECT_EQ(passNames(graph, plan), (std::vector<std::string>{"p0", "p1", "p2", "p3"}));
  for (size_t i = 1; i < plan.size(); ++i) EXPECT_LT(plan[i - 1].pass, plan[i].pass);
}

TEST(RenderGraph, WriteAfterReadWaitsOnTheReader) {
  RenderGraph graph(nullptr, nullptr);
  ImageHandle img = graph.createImage("img", storageDesc());
  addPass(graph, "write", [&](PassBuilder& p) { p.write(img, Use::StorageWriteCompute); });
  addPass(graph, "readRt", [&](PassBuilder& p) {
    p.read(img, Use::StorageReadRayTracing);
    p.sideEffect();
  });
  addPass(graph, "rewrite", [&](PassBuilder& p) {
    p.write(img, Use::StorageWriteCompute);
    p.sideEffect();
  });
  const std::vector<PlannedPass> plan = graph.compile();
  ASSERT_EQ(plan.size(), 3u);
  // Read-after-write first: compute write made visible to ray-tracing storage reads.
  ASSERT_EQ(plan[1].barriers.size(), 1u);
  EXPECT_EQ(plan[1].barriers[0].barrier.srcStages, kCs);
  EXPECT_EQ(plan[1].barriers[0].barrier.srcAccess, kSw);
  EXPECT_EQ(plan[1].barriers[0].barrier.dstStages, kRt);
  EXPECT_EQ(plan[1].barriers[0].barrier.dstAccess, kSr);
  // Write-after-read: an execution dependency on the reader's stage, no layout change.
  ASSERT_EQ(plan[2].barriers.size(), 1u);
  const Barrier& war = plan[2].barriers[0].barrier;
  EXPECT_EQ(war.srcStages, kRt);
  EXPECT_EQ(war.srcAccess, 0u);
  EXPECT_EQ(war.dstStages, kCs);
  EXPECT_EQ(war.dstAccess, kSw);
  EXPECT_EQ(war.oldLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(war.newLayout, VK_IMAGE_LAYOUT_GENERAL);
}

TEST(RenderGraph, WriteAfterSampledReadTransitionsBackAndWaitsOnReader) {
  RenderGraph graph(nullptr, nullptr);
  ImageHandle img = graph.createImage("img", storageDesc());
  addPass(graph, "write", [&](PassBuilder& p) { p.write(img, Use::StorageWriteCompute); });
  addPass(graph, "sampleFs", [&](PassBuilder& p) {
    p.read(img, Use::SampledFragment);
    p.sideEffect();
  });
  addPass(graph, "rewrite", [&](PassBuilder& p) {
    p.write(img, Use::StorageWriteCompute);
    p.sideEffect();
  });
  const std::vector<PlannedPass> plan = graph.compile();
  ASSERT_EQ(plan.size(), 3u);
  ASSERT_EQ(plan[2].barriers.size(), 1u);
  const Barrier& war = plan[2].barriers[0].barrier;
  EXPECT_EQ(war.srcStages, kFs);
  EXPECT_EQ(war.dstStages, kCs);
  EXPECT_EQ(war.oldLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(war.newLayout, VK_IMAGE_LAYOUT_GENERAL);
}

TEST(RenderGraph, FirstWriteOfTransientStartsFromUndefined) {
  RenderGraph graph(nullptr, nullptr);
  ImageHandle img = graph.createImage("img", storageDesc());
  rhi::ImageDesc colorDesc;
  colorDesc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  ImageHandle color = graph.createImage("color", colorDesc);
  addPass(graph, "write", [&](PassBuilder& p) {
    p.write(img, Use::StorageWriteCompute);
    p.write(color, Use::ColorAttachment);
    p.sideEffect();
  });
  const std::vector<PlannedPass> plan = graph.compile();
  ASSERT_EQ(plan.size(), 1u);
  ASSERT_EQ(plan[0].barriers.size(), 2u);
  for (const PlannedBarrier& pb : plan[0].barriers) {
    EXPECT_TRUE(pb.isImage);
    EXPECT_EQ(pb.barrier.oldLayout, VK_IMAGE_LAYOUT_UNDEFINED) << graph.imageName(pb.resource);
    EXPECT_EQ(pb.barrier.srcStages, VK_PIPELINE_STAGE_2_NONE) << graph.imageName(pb.resource);
    EXPECT_EQ(pb.barrier.srcAccess, 0u) << graph.imageName(pb.resource);
  }
  auto it = std::find_if(plan[0].barriers.begin(), plan[0].barriers.end(),
                         [&](const PlannedBarrier& pb) { return pb.resource == img.id; });
  ASSERT_NE(it, plan[0].barriers.end());
  EXPECT_EQ(it->barrier.newLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(it->barrier.dstStages, kCs);
  EXPECT_EQ(it->barrier.dstAccess, kSw);
  it = std::find_if(plan[0].barriers.begin(), plan[0].barriers.end(),
                    [&](const PlannedBarrier& pb) { return pb.resource == color.id; });
  ASSERT_NE(it, plan[0].barriers.end());
  EXPECT_EQ(it->barrier.newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(it->barrier.dstStages, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
}

TEST(RenderGraph, SecondReaderInSameStageNeedsNoBarrier) {
  RenderGraph graph(nullptr, nullptr);
  ImageHandle img = graph.createImage("img", storageDesc());
  addPass(graph, "write", [&](PassBuilder& p) { p.write(img, Use::StorageWriteCompute); });
  addPass(graph, "read1", [&](PassBuilder& p) {
    p.read(img, Use::SampledRayTracing);
    p.sideEffect();
  });
  addPass(graph, "read2", [&](PassBuilder& p) {
    p.read(img, Use::SampledRayTracing);
    p.sideEffect();
  });
  const std::vector<PlannedPass> plan = graph.compile();
  ASSERT_EQ(passNames(graph, plan), (std::vector<std::string>{"write", "read1", "read2"}));
  EXPECT_EQ(plan[1].barriers.size(), 1u);
  EXPECT_TRUE(plan[2].barriers.empty());
}

TEST(RenderGraph, ReaderInAnotherStageStillGetsABarrier) {
  // Guards the previous test against a graph that simply never emits read barriers.
  RenderGraph graph(nullptr, nullptr);
  ImageHandle img = graph.createImage("img", storageDesc());
  addPass(graph, "write", [&](PassBuilder& p) { p.write(img, Use::StorageWriteCompute); });
  addPass(graph, "readRt", [&](PassBuilder& p) {
    p.read(img, Use::SampledRayTracing);
    p.sideEffect();
  });
  addPass(graph, "readFs", [&](PassBuilder& p) {
    p.read(img, Use::SampledFragment);
    p.sideEffect();
  });
  const std::vector<PlannedPass> plan = graph.compile();
  ASSERT_EQ(plan.size(), 3u);
  ASSERT_EQ(plan[2].barriers.size(), 1u);
  EXPECT_EQ(plan[2].barriers[0].barrier.dstStages, kFs);
  EXPECT_EQ(plan[2].barriers[0].barrier.oldLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(plan[2].barriers[0].barrier.newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

TEST(RenderGraph, CulledPassLeavesNoTraceInBarriers) {
  // A dead pass that would have transitioned the image must not change what live passes see.
  RenderGraph graph(nullptr, nullptr);
  ImageHandle img = graph.createImage("img", storageDesc());
  ImageHandle junk = graph.createImage("junk", storageDesc());
  addPass(graph, "write", [&](PassBuilder& p) { p.write(img, Use::StorageWriteCompute); });
  addPass(graph, "deadSampler", [&](PassBuilder& p) {
    p.read(img, Use::SampledFragment);
    p.write(junk, Use::StorageWriteCompute);
  });
  addPass(graph, "storageRead", [&](PassBuilder& p) {
    p.read(img, Use::StorageReadCompute);
    p.sideEffect();
  });
  const std::vector<PlannedPass> plan = graph.compile();
  ASSERT_EQ(passNames(graph, plan), (std::vector<std::string>{"write", "storageRead"}));
  ASSERT_EQ(plan[1].barriers.size(), 1u);
  EXPECT_EQ(plan[1].barriers[0].barrier.oldLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(plan[1].barriers[0].barrier.newLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(plan[1].barriers[0].barrier.srcStages, kCs);
  EXPECT_EQ(plan[1].barriers[0].barrier.srcAccess, kSw);
}

TEST(RenderGraph, CompileIsPureAndRepeatable) {
  // Planning twice must give the same barriers: compile() may not advance any resource state.
  RenderGraph graph(nullptr, nullptr);
  ImageHandle img = graph.createImage("img", storageDesc());
  addPass(graph, "write", [&](PassBuilder& p) { p.write(img, Use::StorageWriteCompute); });
  addPass(graph, "read", [&](PassBuilder& p) {
    p.read(img, Use::SampledRayTracing);
    p.sideEffect();
  });
  auto first = graph.compile();
  auto second = graph.compile();
  ASSERT_EQ(first.size(), second.size());
  for (size_t i = 0; i < first.size(); ++i) {
    ASSERT_EQ(first[i].barriers.size(), second[i].barriers.size());
    for (size_t b = 0; b < first[i].barriers.size(); ++b) {
      EXPECT_EQ(first[i].barriers[b].barrier.oldLayout, second[i].barriers[b].barrier.oldLayout);
      EXPECT_EQ(first[i].barriers[b].barrier.srcStages, second[i].barriers[b].barrier.srcStages);
    }
  }
  EXPECT_EQ(first[0].barriers[0].barrier.oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
}

}  // namespace
}  // namespace rayster::graph
