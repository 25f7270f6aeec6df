// The C++ structs in kernels/shared/shared_*.h and the blocks glslang laid out for the shaders must agree byte for
// byte. The embedded SPIR-V carries the std430 offsets glslang chose (OpMemberDecorate ... Offset) and the
// member names (OpMemberName); this test reads them back and compares with the C++ offsets.
#include <gtest/gtest.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "kernels/shared/shared_step.h"
#include "kernels/shared/spirv.h"
#include "model/params.h"

namespace gb {
namespace {

struct Member {
  std::string name;
  uint32_t offset = ~0u;
};

// Members (name and byte offset) of the struct type called `typeName` in a SPIR-V module.
std::vector<Member> structLayout(std::span<const uint32_t> words, const std::string& typeName) {
  constexpr uint32_t opName = 5, opMemberName = 6, opMemberDecorate = 72, decorationOffset = 35;
  auto literal = [&](size_t at, size_t end) {
    std::string s;
    for (size_t w = at; w < end; ++w)
      for (int b = 0; b < 4; ++b) {
        const char c = static_cast<char>((words[w] >> (8 * b)) & 0xff);
        if (c == 0) return s;
        s += c;
      }
    return s;
  };
  uint32_t typeId = 0;
  std::map<uint32_t, Member> members;
  std::map<uint32_t, std::map<uint32_t, std::string>> names;
  std::map<uint32_t, std::map<uint32_t, uint32_t>> offsets;
  for (size_t at = 5; at < words.size();) {
    const uint32_t count = words[at] >> 16, op = words[at] & 0xffff;
    if (count == 0) break;
    if (op == opName && literal(at + 2, at + count) == typeName) typeId = words[at + 1];
    if (op == opMemberName) names[words[at + 1]][words[at + 2]] = literal(at + 3, at + count);
    if (op == opMemberDecorate && words[at + 3] == decorationOffset)
      offsets[words[at + 1]][words[at + 2]] = words[at + 4];
    at += count;
  }
  std::vector<Member> out;
  for (const auto& [index, name] : names[typeId])
    out.push_back({name, offsets[typeId].count(index) ? offsets[typeId][index] : ~0u});
  return out;
}

TEST(SharedLayout, ParamsBlockHasTheCppLayoutInEveryShader) {
  // Params is a run of 4-byte scalars: member k sits at byte 4k in C++; std430 must agree.
  for (auto kernel : {kernels::Kernel::Forces, kernels::Kernel::FilmState, kernels::Kernel::AirTransfer}) {
    const auto members = structLayout(kernels::spirv(kernel), "Params");
    ASSERT_EQ(members.size() * 4, sizeof(Params)) << kernels::kernelName(kernel);
    for (size_t k = 0; k < members.size(); ++k)
      EXPECT_EQ(members[k].offset, 4 * k) << kernels::kernelName(kernel) << ": " << members[k].name;
    EXPECT_EQ(members.front().name, "frameTime");
    EXPECT_EQ(members.back().name, "gibbsElasticity");
  }
}

TEST(SharedLayout, StepUniformsAndPushConstantsMatchTheCppOffsets) {
  using gpu::StepUniformsBlock;
  const std::map<std::string, size_t> expected = {{"leftPosition", offsetof(StepUniformsBlock, leftPosition)},
                                                  {"leftVelocity", offsetof(StepUniformsBlock, leftVelocity)},
                                                  {"rightPosition", offsetof(StepUniformsBlock, rightPosition)},
                                                  {"rightVelocity", offsetof(StepUniformsBlock, rightVelocity)},
                                                  {"wireCenter", offsetof(StepUniformsBlock, wireCenter)},
                                                  {"wireAxis", offsetof(StepUniformsBlock, wireAxis)},
                                                  {"wireDown", offsetof(StepUniformsBlock, wireDown)},
                                                  {"volumeOrigin", offsetof(StepUniformsBlock, volumeOrigin)},
                                                  {"dt", offsetof(StepUniformsBlock, dt)},
                                                  {"leftInflowWeight", offsetof(StepUniformsBlock, leftInflowWeight)},
                                                  {"airVolume", offsetof(StepUniformsBlock, airVolume)},
                                                  {"wandAlignment", offsetof(StepUniformsBlock, wandAlignment)},
                                                  {"wireHalfWidth", offsetof(StepUniformsBlock, wireHalfWidth)},
                                                  {"wireDepth", offsetof(StepUniformsBlock, wireDepth)},
                                                  {"referenceVolume", offsetof(StepUniformsBlock, referenceVolume)},
                                                  {"wireKind", offsetof(StepUniformsBlock, wireKind)},
                                                  {"closed", offsetof(StepUniformsBlock, closed)},
                                                  {"drainageDt", offsetof(StepUniformsBlock, drainageDt)},
                                                  {"wireArea", offsetof(StepUniformsBlock, wireArea)},
                                                  {"frameTime", offsetof(StepUniformsBlock, frameTime)},
                                                  {"solverSweeps", offsetof(StepUniformsBlock, solverSweeps)}};
  const auto members = structLayout(kernels::spirv(kernels::Kernel::Integrate), "StepUniformsBlock");
  ASSERT_EQ(members.size(), expected.size());
  for (const Member& m : members) {
    ASSERT_TRUE(expected.count(m.name)) << m.name;
    EXPECT_EQ(m.offset, expected.at(m.name)) << m.name;
  }
  const auto push = structLayout(kernels::spirv(kernels::Kernel::TreeSum), "PushBlock");
  ASSERT_EQ(push.size(), 9u);
  EXPECT_EQ(push[0].name, "count");
  EXPECT_EQ(push[3].offset, offsetof(gpu::PushBlock, reduceFlags));
  EXPECT_EQ(push[4].offset, offsetof(gpu::PushBlock, triangles));
  EXPECT_EQ(push[5].offset, offsetof(gpu::PushBlock, first));
  EXPECT_EQ(push[6].offset, offsetof(gpu::PushBlock, patches));
  EXPECT_EQ(push[7].offset, offsetof(gpu::PushBlock, solverParticles));
  EXPECT_EQ(push[8].offset, offsetof(gpu::PushBlock, ruleShare));
}

}  // namespace
}  // namespace gb
