#include "model/params.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace gb {
namespace {

TEST(Params, DefaultsAreValidAndInsideThePapersRanges) {
  const Params p;
  EXPECT_TRUE(validate(p).empty());
  // Table 2 ranges, in the paper's own numbers.
  EXPECT_GE(p.elasticityWeight, 12.0f);
  EXPECT_LE(p.elasticityWeight, 13.0f);
  EXPECT_GE(p.areaWeight, 0.02f);
  EXPECT_LE(p.areaWeight, 0.05f);
  EXPECT_GE(p.airDirectionThreshold, 0.5f);
  EXPECT_LE(p.airDirectionThreshold, 0.7f);
  EXPECT_FLOAT_EQ(p.frameTime, 0.02f);
  EXPECT_GE(p.thicknessThreshold, 20e-9f);
  EXPECT_LE(p.thicknessThreshold, 50e-9f);
  EXPECT_GE(p.sticky, 20.0f);
  EXPECT_LE(p.sticky, 30.0f);
  EXPECT_GE(p.collisionThreshold, 1.5f);
  EXPECT_LE(p.collisionThreshold, 2.0f);
  EXPECT_FLOAT_EQ(p.pressureCoefficient, 1010.0f);
}

TEST(Params, AreaWeightMapsToInitialThickness) {
  Params p;
  p.areaWeight = 0.02f;
  EXPECT_FLOAT_EQ(initialThickness(p), 2e-6f);  // w_e x 100 um
}

TEST(Params, AbsurdValuesAreRejectedByName) {
  Params p;
  p.solution = 7.0f;
  p.frameTime = -1.0f;
  p.filmInertia = std::numeric_limits<float>::quiet_NaN();
  const auto errors = validate(p);
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_NE(errors[0].find("frameTime = -1"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find("filmInertia = nan"), std::string::npos) << errors[1];
  EXPECT_NE(errors[2].find("solution = 7 is out of range [0.01, 1]"), std::string::npos) << errors[2];
}

}  // namespace
}  // namespace gb

namespace gb {
namespace {

TEST(Params, EveryFieldHasOneNameAndTheTableCoversTheBlock) {
  // Params holds only 4-byte scalars (shared_params.h), so the table covers it iff it has sizeof / 4 distinct
  // fields; distinct member pointers are checked through the offsets they address.
  const auto fields = paramFields();
  EXPECT_EQ(fields.size() * 4, sizeof(Params));
  Params p;
  std::set<const void*> addresses;
  std::set<std::string> names;
  for (const ParamField& f : fields) {
    addresses.insert(f.real ? static_cast<const void*>(&(p.*f.real)) : static_cast<const void*>(&(p.*f.integer)));
    names.insert(f.name);
  }
  EXPECT_EQ(addresses.size(), fields.size());
  EXPECT_EQ(names.size(), fields.size());
}

TEST(Params, SetByNameChecksTheNameAndWholeNumbers) {
  Params p;
  setParameter(p, "sticky", 27.5);
  EXPECT_EQ(p.sticky, 27.5f);
  setParameter(p, "holeOpening", 1);
  EXPECT_EQ(p.holeOpening, 1);
  EXPECT_THROW(setParameter(p, "stiky", 1), std::invalid_argument);
  EXPECT_THROW(setParameter(p, "maxSubsteps", 2.5), std::invalid_argument);
}

}  // namespace
}  // namespace gb
