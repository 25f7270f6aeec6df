#pragma once
// The Vulkan backend: the stages of cpu-reference/stages/stages.h as compute shaders (kernels/) over one storage
// buffer per attribute. A batch of substeps is recorded into one command buffer and submitted once, with a
// barrier only where a stage reads what an earlier one wrote. Topology stays on the CPU: load() takes a
// changed film, store() brings the state back.

#include <memory>

#include "device_film.h"
#include "stepper.h"

namespace gb {

class VulkanContext;

class VulkanStepper final : public Stepper {
 public:
  explicit VulkanStepper(std::shared_ptr<const VulkanContext> context);
  ~VulkanStepper() override;
  VulkanStepper(const VulkanStepper&) = delete;  // owns device objects
  VulkanStepper& operator=(const VulkanStepper&) = delete;

  [[nodiscard]] std::string name() const override;
  void load(const Params& params, Film& film) override;
  float run(std::span<const StepUniforms> substeps) override;
  float runStage(Stage stage, const StepUniforms& uniforms) override;
  void store(Film& film) override;
  void updateContacts(const Film& film) override;
  void updateRestLengths(const Film& film) override;
  void updateTopology(const Params& params, Film& film) override;

  [[nodiscard]] const VulkanContext& context() const;
  // The film's buffers as the last batch left them, for a renderer on the same device to read in place.
  [[nodiscard]] DeviceFilm deviceFilm();
  // The device, for a renderer that reads deviceFilm() in place.
  [[nodiscard]] std::shared_ptr<const VulkanContext> sharedContext() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gb
