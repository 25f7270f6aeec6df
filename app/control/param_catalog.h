#pragma once
// The model's parameters as show control presents them (live --control, OSC /giantbubble/param/NAME): each field of
// the parameter table (params.h) with its group and meaning as the documentation gives them, the group from the
// section comments of kernels/shared_params.h and the meaning from the table in docs/model.md, both embedded at
// build time so the two cannot drift apart.

#include <span>
#include <string>

#include "model/params.h"

namespace gb {

// When a set parameter takes effect in a running show.
enum class ParamTiming {
  Live,      // from the next frame
  NextFilm,  // at the next dip: it shapes a film as it is made (its particles, liquid, rest lengths)
  Start,     // only when the show starts (--param): the show's clock is built on it
};

struct ParamInfo {
  const ParamField* field = nullptr;
  std::string group;        // "Air (Section 5.2, Eqs. 5-11)" without its references: "Air"
  std::string description;  // docs/model.md's meaning
  ParamTiming timing = ParamTiming::Live;
  [[nodiscard]] std::string unit() const;  // the unit without its leading space; "" when dimensionless
  [[nodiscard]] bool integer() const { return field->integer != nullptr; }
};

// Every parameter of paramFields(), in its order.
std::span<const ParamInfo> paramCatalog();
const ParamInfo* findParamInfo(const std::string& name);

// A parameter's value in a block, as a double.
double paramValue(const Params& params, const ParamField& field);

}  // namespace gb
