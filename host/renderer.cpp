#include "host/renderer.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "host/device_buffer.h"
#include "host/device_image.h"
#include "host/film_swirls.h"
#include "host/thin_film.h"
#include "kernels/render/render_shared.h"
#include "kernels/render/render_spirv.h"
#include "kernels/render/thin_film_lut.h"

namespace gb {

using gpu::RenderUniforms;
using kernels::RenderShader;
static_assert(offsetof(RenderUniforms, skyRays) == 64);
static_assert(offsetof(RenderUniforms, cameraPosition) == 128);
static_assert(offsetof(RenderUniforms, skyIrradiance) == 160);
static_assert(offsetof(RenderUniforms, horizon) == 192);
static_assert(offsetof(RenderUniforms, particles) == 208);
static_assert(offsetof(RenderUniforms, cameraImage) == 256);
static_assert(sizeof(RenderUniforms) == 288);

Colouring colouringFromName(const std::string& name) {
  if (name == "interference") return Colouring::Interference;
  if (name == "thickness") return Colouring::Thickness;
  if (name == "airflow") return Colouring::AirFlow;
  throw std::invalid_argument("unknown colouring '" + name + "' (interference, thickness, airflow)");
}

const char* colouringName(Colouring colouring) {
  switch (colouring) {
    case Colouring::Interference:
      return "interference";
    case Colouring::Thickness:
      return "thickness";
    case Colouring::AirFlow:
      return "airflow";
  }
  return "?";
}

namespace {

constexpr vk::Format kHdrFormat = vk::Format::eR16G16B16A16Sfloat;
constexpr vk::Format kRevealFormat = vk::Format::eR16Sfloat;
constexpr vk::Format kDepthFormat = vk::Format::eD32Sfloat;
// The resolve writes linear radiance; the format's sRGB encoding on store is cheaper on lavapipe than the curve in
// the shader (three pow per pixel), and the bytes read back are sRGB as PNG and video expect.
constexpr vk::Format kOutputFormat = vk::Format::eR8G8B8A8Srgb;

using Stage = vk::PipelineStageFlagBits;
using Access = vk::AccessFlagBits;
using Layout = vk::ImageLayout;

vk::AttachmentDescription attachment(vk::Format format, vk::AttachmentLoadOp load, vk::AttachmentStoreOp store,
                                     Layout initial, Layout final,
                                     vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1) {
  return vk::AttachmentDescription({}, format, samples, load, store, vk::AttachmentLoadOp::eDontCare,
                                   vk::AttachmentStoreOp::eDontCare, initial, final);
}

// A one-subpass render pass; `before` and `after` are its dependencies on the commands outside it. Attachments
// are the colours, then the depth (if any), then, when `resolved`, one single-sampled image per colour that
// the multisampled colour is resolved into at the end of the pass.
vk::raii::RenderPass makeRenderPass(const vk::raii::Device& device,
                                    const std::vector<vk::AttachmentDescription>& attachments, uint32_t colourCount,
                                    bool hasDepth, bool resolved, const vk::SubpassDependency& before,
                                    const vk::SubpassDependency& after) {
  std::vector<vk::AttachmentReference> colours, resolves;
  for (uint32_t i = 0; i < colourCount; ++i) colours.emplace_back(i, Layout::eColorAttachmentOptimal);
  const uint32_t firstResolve = colourCount + (hasDepth ? 1 : 0);
  for (uint32_t i = 0; resolved && i < colourCount; ++i)
    resolves.emplace_back(firstResolve + i, Layout::eColorAttachmentOptimal);
  const vk::AttachmentReference depth(colourCount, Layout::eDepthStencilAttachmentOptimal);
  const vk::SubpassDescription subpass({}, vk::PipelineBindPoint::eGraphics, {}, colours, resolves,
                                       hasDepth ? &depth : nullptr);
  const std::array<vk::SubpassDependency, 2> dependencies{before, after};
  return vk::raii::RenderPass(device, vk::RenderPassCreateInfo({}, attachments, subpass, dependencies));
}

struct PipelineDesc {
  RenderShader vertex, fragment;
  vk::PrimitiveTopology topology = vk::PrimitiveTopology::eTriangleList;
  bool depthTest = true, depthWrite = true;
  std::vector<vk::PipelineColorBlendAttachmentState> blends;
  bool multisampled = true;  // drawn into the multisampled targets (all but the resolve)
};

vk::PipelineColorBlendAttachmentState opaqueBlend() {
  using C = vk::ColorComponentFlagBits;
  vk::PipelineColorBlendAttachmentState s;
  s.colorWriteMask = C::eR | C::eG | C::eB | C::eA;
  return s;
}

// Weighted blended OIT. Both targets add (one, one): accum sums the weighted colours, reveal sums -log(1 - alpha),
// whose exponential in the resolve is the product of the sheets' transmittances. The usual multiplicative reveal
// blend would need a different blend per attachment (the independentBlend feature); a sum needs none.
std::vector<vk::PipelineColorBlendAttachmentState> transparencyBlends() {
  using C = vk::ColorComponentFlagBits;
  using F = vk::BlendFactor;
  const vk::PipelineColorBlendAttachmentState add(true, F::eOne, F::eOne, vk::BlendOp::eAdd, F::eOne, F::eOne,
                                                  vk::BlendOp::eAdd, C::eR | C::eG | C::eB | C::eA);
  return {add, add};
}

}  // namespace

struct Renderer::Impl {
  std::shared_ptr<const VulkanContext> ctx;
  RenderOptions options;
  vk::Extent2D extent;

  vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
  DeviceImage opaque, depth, accum, reveal, output;
  DeviceImage sky;  // the environment along each pixel's view ray (sky.frag), drawn when the view turns
  DeviceImage opaqueSamples, accumSamples, revealSamples;  // the multisampled targets, resolved into the above
  vk::raii::RenderPass opaquePass{nullptr}, filmPass{nullptr}, compositePass{nullptr}, skyPass{nullptr};
  vk::raii::Framebuffer opaqueTarget{nullptr}, filmTarget{nullptr}, compositeTarget{nullptr}, skyTarget{nullptr};
  vk::raii::Sampler linearSampler{nullptr}, nearestSampler{nullptr};
  DeviceImage lut, environment;

  vk::raii::DescriptorSetLayout sceneLayout{nullptr}, compositeLayout{nullptr};
  vk::raii::PipelineLayout pipelineLayout{nullptr};
  std::vector<vk::raii::ShaderModule> modules;  // indexed by RenderShader
  vk::raii::Pipeline props{nullptr}, droplets{nullptr}, film{nullptr}, composite{nullptr}, skyLookup{nullptr},
      cameraImage{nullptr};
  // What the sky image shows: the sky is at infinity, so it depends on the view's direction and zoom and the
  // image's size, not on where the camera is. Empty: not drawn yet (or the targets were made again).
  struct SkyView {
    std::array<float, 16> rays;  // the camera's skyRays
    uint32_t width, height;
    bool operator==(const SkyView&) const = default;
  };
  std::optional<SkyView> skyDrawnFor;
  vk::raii::DescriptorPool pool{nullptr};
  vk::raii::DescriptorSet compositeSet{nullptr};

  // What a frame in flight owns: its commands and fence, the buffers they read (the uploaded film, props,
  // droplets, swirls, uniforms, and the descriptor set naming them) and the pixels they read back. Two
  // slots: `run` submits a frame while the one before is still drawn. The targets are shared: frames run in
  // submission order on the one queue, and each render pass waits for the passes before it that touch its
  // attachments (its external dependencies).
  struct FrameSlot {
    vk::raii::CommandBuffer commands{nullptr};
    vk::raii::CommandBuffer snapshotCommands{nullptr};  // copies a film read on the device into the buffers below
    vk::raii::Fence done{nullptr};
    bool inFlight = false;    // `commands` submitted and not yet waited for
    bool filmCopied = false;  // the film was copied on the device (copyOnTheDevice), not uploaded from the host
    Renderer::Ticket ticket = 0;
    // The frame's own film (uploaded from the host, or copied from the stepper's buffers), props, droplets, swirls.
    DeviceBuffer uniforms, position, normal, thickness, airFlow, triangles, propsMesh, dropletBuffer, variation;
    DeviceBuffer cameraColour, cameraDepth;  // the mirror view's camera image
    DeviceBuffer readback;
    uint32_t propsVertices = 0, dropletCount = 0;
    bool drawsCameraImage = false;
    vk::raii::DescriptorSet sceneSet{nullptr};
    vk::raii::QueryPool timestamps{nullptr};  // the frame's first and last command, on a device whose clock the
                                              // host can read (VulkanContext::timestampsOnHostClock)
  };
  std::vector<Renderer::BusyInterval> drawn;  // when the device drew the frames waited for, oldest first
  std::array<FrameSlot, 2> slots;
  size_t current = 0;            // the slot of the latest submit
  Renderer::Ticket tickets = 0;  // submits so far
  FrameSlot& slot() { return slots[current]; }
  const FrameSlot& slot() const { return slots[current]; }
  std::array<Vec3, 2> ambient;  // mean environment radiance above and below the horizon
  Vec3 horizon;                 // just below it
  float hazeDistance = 0.0f;    // over which the ground fades into it (EnvironmentImage::hazeDistance)
  Vec3 keyLight;
  float keyStrength = 0.0f;
  FilmSwirls swirls;

  Impl(std::shared_ptr<const VulkanContext> context, const RenderOptions& o, const EnvironmentImage& env)
      : ctx(std::move(context)), options(o), swirls(o.thicknessVariation) {
    samples = supportedSamples(o.samples);
    setExtent(o.width, o.height);
    makeTargets();
    makeSamplersAndTextures(env);
    ambient = hemisphereMeans(env);
    horizon = horizonRadiance(env);
    hazeDistance = env.hazeDistance;
    keyLight = env.keyLight;
    keyStrength = env.keyStrength;
    makeLayouts();
    makePipelines();
    makeDescriptors();
    makeImageBuffers();
    for (FrameSlot& f : slots) {
      f.uniforms = DeviceBuffer(*ctx, sizeof(RenderUniforms));
      f.commands = ctx->newCommandBuffer();
      f.snapshotCommands = ctx->newCommandBuffer();
      f.done = ctx->newFence();
      if (ctx->timestampsOnHostClock())
        f.timestamps = vk::raii::QueryPool(ctx->device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, 2));
    }
  }
  ~Impl() {
    for (FrameSlot& f : slots)  // before their objects go
      if (f.inFlight) (void)ctx->device.waitForFences({*f.done}, VK_TRUE, UINT64_MAX);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  void wait(FrameSlot& f) {
    if (!f.inFlight) return;
    f.inFlight = false;  // also when the wait throws: a lost device is not waited for twice
    ctx->waitFor(f.done);
    if (*f.timestamps) noteWhenDrawn(f.timestamps);
  }
  void noteWhenDrawn(const vk::raii::QueryPool& timestamps) {
    const std::optional<Renderer::BusyInterval> interval = ctx->busyInterval(timestamps);
    if (!interval) return;
    // A caller that never takes them keeps only the latest: a show runs for hours.
    constexpr size_t kKept = 1024;
    if (drawn.size() >= kKept) drawn.erase(drawn.begin());
    drawn.push_back(*interval);
  }
  void waitForAll() {
    // Oldest first: the other slot's frame was submitted before the current one.
    wait(slots[1 - current]);
    wait(slots[current]);
  }

  void setExtent(int width, int height) {
    const vk::PhysicalDeviceLimits limits = ctx->physical.getProperties().limits;
    double heapBytes = 0;
    const vk::PhysicalDeviceMemoryProperties memory = ctx->physical.getMemoryProperties();
    for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
      if (memory.memoryHeaps[h].flags & vk::MemoryHeapFlagBits::eDeviceLocal)
        heapBytes = std::max(heapBytes, static_cast<double>(memory.memoryHeaps[h].size));
    const std::string problem =
        renderSizeProblem(width, height, static_cast<int>(samples), static_cast<int>(limits.maxImageDimension2D),
                          heapBytes, ctx->info().name);
    if (!problem.empty()) throw std::invalid_argument(problem);
    options.width = width;
    options.height = height;
    extent = vk::Extent2D(static_cast<uint32_t>(width), static_cast<uint32_t>(height));
  }

  void makeImageBuffers() {  // host memory for the read-back images
    for (FrameSlot& f : slots)
      f.readback = DeviceBuffer(*ctx, 4ull * extent.width * extent.height, DeviceBuffer::Placement::Readback);
  }

  void resize(int width, int height) {
    setExtent(width, height);
    waitForAll();
    ctx->device.waitIdle();
    // The descriptor sets go before their pool, the pipelines and modules before they are made again.
    for (FrameSlot& f : slots) f.sceneSet = nullptr;
    compositeSet = nullptr;
    props = nullptr;
    droplets = nullptr;
    film = nullptr;
    composite = nullptr;
    skyLookup = nullptr;
    cameraImage = nullptr;
    modules.clear();
    makeTargets();
    makePipelines();
    makeDescriptors();
    makeImageBuffers();
  }

  // The sample count of the targets: what colour and depth targets both support, up to `wanted`.
  vk::SampleCountFlagBits supportedSamples(int wanted) const {
    const vk::PhysicalDeviceLimits limits = ctx->physical.getProperties().limits;
    const vk::SampleCountFlags both = limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;
    // Not every count need be supported (lavapipe has 1 and 4 only): the largest supported one up to `wanted`.
    for (uint32_t count = 64; count > 1; count /= 2)
      if (count <= static_cast<uint32_t>(std::max(wanted, 1)) && (both & static_cast<vk::SampleCountFlagBits>(count)))
        return static_cast<vk::SampleCountFlagBits>(count);
    return vk::SampleCountFlagBits::e1;
  }

  void makeTargets() {
    using U = vk::ImageUsageFlagBits;
    const vk::raii::Device& device = ctx->device;
    const bool msaa = samples != vk::SampleCountFlagBits::e1;
    const auto colourTarget = [&](vk::Format format) {
      return DeviceImage(*ctx, extent, format, U::eColorAttachment, vk::ImageAspectFlagBits::eColor, samples);
    };
    opaque = DeviceImage(*ctx, extent, kHdrFormat, U::eColorAttachment | U::eSampled);
    depth =
        DeviceImage(*ctx, extent, kDepthFormat, U::eDepthStencilAttachment, vk::ImageAspectFlagBits::eDepth, samples);
    accum = DeviceImage(*ctx, extent, kHdrFormat, U::eColorAttachment | U::eSampled);
    reveal = DeviceImage(*ctx, extent, kRevealFormat, U::eColorAttachment | U::eSampled);
    output = DeviceImage(*ctx, extent, kOutputFormat, U::eColorAttachment | U::eTransferSrc | U::eTransferDst);
    if (msaa) {
      opaqueSamples = colourTarget(kHdrFormat);
      accumSamples = colourTarget(kHdrFormat);
      revealSamples = colourTarget(kRevealFormat);
    }
    using Load = vk::AttachmentLoadOp;
    using Store = vk::AttachmentStoreOp;
    const vk::PipelineStageFlags draw =
        Stage::eColorAttachmentOutput | Stage::eEarlyFragmentTests | Stage::eLateFragmentTests;
    const vk::AccessFlags drawWrites = Access::eColorAttachmentWrite | Access::eDepthStencilAttachmentWrite;
    // A colour the pass clears and the resolve samples: drawn straight into it, or drawn multisampled (the
    // samples are not kept) and resolved into it.
    const auto sampledColour = [&](vk::Format format) {
      std::vector<vk::AttachmentDescription> a;
      if (msaa)
        a.push_back(attachment(format, Load::eClear, Store::eDontCare, Layout::eUndefined,
                               Layout::eColorAttachmentOptimal, samples));
      else
        a.push_back(
            attachment(format, Load::eClear, Store::eStore, Layout::eUndefined, Layout::eShaderReadOnlyOptimal));
      return a;
    };
    const auto resolveTo = [&](vk::Format format) {
      return attachment(format, Load::eDontCare, Store::eStore, Layout::eUndefined, Layout::eShaderReadOnlyOptimal);
    };
    // Opaque pass: waits for last frame's resolve to have read its colour; its colour is sampled and its depth
    // tested by the passes after it.
    std::vector<vk::AttachmentDescription> opaqueAttachments = sampledColour(kHdrFormat);
    opaqueAttachments.push_back(attachment(kDepthFormat, Load::eClear, Store::eStore, Layout::eUndefined,
                                           Layout::eDepthStencilAttachmentOptimal, samples));
    if (msaa) opaqueAttachments.push_back(resolveTo(kHdrFormat));
    opaquePass = makeRenderPass(device, opaqueAttachments, 1, true, msaa,
                                {VK_SUBPASS_EXTERNAL, 0, Stage::eFragmentShader | draw, draw, {}, drawWrites},
                                {0, VK_SUBPASS_EXTERNAL, draw, Stage::eFragmentShader | draw, drawWrites,
                                 Access::eShaderRead | Access::eDepthStencilAttachmentRead});
    // Film pass: tests against the opaque depth without writing it; accum and reveal go to the resolve.
    std::vector<vk::AttachmentDescription> filmAttachments = sampledColour(kHdrFormat);
    filmAttachments.push_back(sampledColour(kRevealFormat)[0]);
    filmAttachments.push_back(attachment(kDepthFormat, Load::eLoad, Store::eDontCare,
                                         Layout::eDepthStencilAttachmentOptimal, Layout::eDepthStencilAttachmentOptimal,
                                         samples));
    if (msaa) {
      filmAttachments.push_back(resolveTo(kHdrFormat));
      filmAttachments.push_back(resolveTo(kRevealFormat));
    }
    filmPass = makeRenderPass(device, filmAttachments, 2, true, msaa,
                              {VK_SUBPASS_EXTERNAL, 0, Stage::eFragmentShader | draw, draw, drawWrites,
                               Access::eColorAttachmentWrite | Access::eDepthStencilAttachmentRead},
                              {0, VK_SUBPASS_EXTERNAL, draw, Stage::eFragmentShader | draw,
                               Access::eColorAttachmentWrite, Access::eShaderRead});
    // Resolve: its output is then copied out (readback, window blit).
    compositePass = makeRenderPass(
        device,
        {attachment(kOutputFormat, Load::eDontCare, Store::eStore, Layout::eUndefined, Layout::eTransferSrcOptimal)}, 1,
        false, false,
        {VK_SUBPASS_EXTERNAL,
         0,
         Stage::eTransfer | Stage::eColorAttachmentOutput,
         Stage::eColorAttachmentOutput,
         {},
         Access::eColorAttachmentWrite},
        {0, VK_SUBPASS_EXTERNAL, Stage::eColorAttachmentOutput, Stage::eTransfer, Access::eColorAttachmentWrite,
         Access::eTransferRead});
    std::vector<vk::ImageView> opaqueViews{msaa ? opaqueSamples.view() : opaque.view(), depth.view()};
    std::vector<vk::ImageView> filmViews{msaa ? accumSamples.view() : accum.view(),
                                         msaa ? revealSamples.view() : reveal.view(), depth.view()};
    if (msaa) {
      opaqueViews.push_back(opaque.view());
      filmViews.insert(filmViews.end(), {accum.view(), reveal.view()});
    }
    const vk::ImageView outputView = output.view();
    opaqueTarget = vk::raii::Framebuffer(
        device, vk::FramebufferCreateInfo({}, *opaquePass, opaqueViews, extent.width, extent.height, 1));
    filmTarget = vk::raii::Framebuffer(
        device, vk::FramebufferCreateInfo({}, *filmPass, filmViews, extent.width, extent.height, 1));
    compositeTarget = vk::raii::Framebuffer(
        device, vk::FramebufferCreateInfo({}, *compositePass, outputView, extent.width, extent.height, 1));
    // Sky: waits for the resolves before it to have read the sky image, and is read by the resolves after it.
    sky = DeviceImage(*ctx, extent, kHdrFormat, U::eColorAttachment | U::eSampled);
    skyPass = makeRenderPass(
        device,
        {attachment(kHdrFormat, Load::eDontCare, Store::eStore, Layout::eUndefined, Layout::eShaderReadOnlyOptimal)}, 1,
        false, false,
        {VK_SUBPASS_EXTERNAL,
         0,
         Stage::eFragmentShader,
         Stage::eColorAttachmentOutput,
         {},
         Access::eColorAttachmentWrite},
        {0, VK_SUBPASS_EXTERNAL, Stage::eColorAttachmentOutput, Stage::eFragmentShader, Access::eColorAttachmentWrite,
         Access::eShaderRead});
    const vk::ImageView skyView = sky.view();
    skyTarget =
        vk::raii::Framebuffer(device, vk::FramebufferCreateInfo({}, *skyPass, skyView, extent.width, extent.height, 1));
    skyDrawnFor.reset();
  }

  void makeSamplersAndTextures(const EnvironmentImage& env) {
    using F = vk::Filter;
    using A = vk::SamplerAddressMode;
    linearSampler = vk::raii::Sampler(
        ctx->device, vk::SamplerCreateInfo({}, F::eLinear, F::eLinear, vk::SamplerMipmapMode::eNearest, A::eClampToEdge,
                                           A::eRepeat, A::eClampToEdge));
    nearestSampler = vk::raii::Sampler(
        ctx->device, vk::SamplerCreateInfo({}, F::eNearest, F::eNearest, vk::SamplerMipmapMode::eNearest,
                                           A::eClampToEdge, A::eClampToEdge, A::eClampToEdge));
    const ThinFilmLut table = buildThinFilmLut(GB_FILM_INDEX);
    lut = uploadTexture(*ctx, table.width, table.height, table.rgba);
    std::vector<float> rgba(static_cast<size_t>(env.width) * env.height * 4, 1.0f);
    for (size_t i = 0; i < static_cast<size_t>(env.width) * env.height; ++i)
      for (size_t c = 0; c < 3; ++c) rgba[4 * i + c] = env.rgb[3 * i + c];
    environment = uploadTexture(*ctx, env.width, env.height, rgba);
  }

  void makeLayouts() {
    using D = vk::DescriptorType;
    const auto all = vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment;
    std::vector<vk::DescriptorSetLayoutBinding> scene;
    for (uint32_t b = 0; b < GB_RENDER_SCENE_BINDINGS; ++b)
      scene.emplace_back(
          b, b == GB_RENDER_LUT || b == GB_RENDER_ENVIRONMENT ? D::eCombinedImageSampler : D::eStorageBuffer, 1, all);
    std::vector<vk::DescriptorSetLayoutBinding> resolve;
    for (uint32_t b : {GB_COMPOSITE_OPAQUE, GB_COMPOSITE_ACCUM, GB_COMPOSITE_REVEAL, GB_COMPOSITE_SKY})
      resolve.emplace_back(b, D::eCombinedImageSampler, 1, vk::ShaderStageFlagBits::eFragment);
    sceneLayout = vk::raii::DescriptorSetLayout(ctx->device, vk::DescriptorSetLayoutCreateInfo({}, scene));
    compositeLayout = vk::raii::DescriptorSetLayout(ctx->device, vk::DescriptorSetLayoutCreateInfo({}, resolve));
    const std::array<vk::DescriptorSetLayout, 2> layouts{*sceneLayout, *compositeLayout};
    pipelineLayout = vk::raii::PipelineLayout(ctx->device, vk::PipelineLayoutCreateInfo({}, layouts));
  }

  vk::raii::Pipeline makePipeline(const PipelineDesc& d, const vk::raii::RenderPass& pass) {
    const vk::PipelineShaderStageCreateInfo stages[] = {
        {{}, vk::ShaderStageFlagBits::eVertex, *modules[static_cast<size_t>(d.vertex)], "main"},
        {{}, vk::ShaderStageFlagBits::eFragment, *modules[static_cast<size_t>(d.fragment)], "main"}};
    const vk::PipelineVertexInputStateCreateInfo vertexInput;  // vertices are pulled from storage buffers
    const vk::PipelineInputAssemblyStateCreateInfo assembly({}, d.topology);
    const vk::Viewport viewport(0, 0, static_cast<float>(extent.width), static_cast<float>(extent.height), 0, 1);
    const vk::Rect2D scissor({0, 0}, extent);
    const vk::PipelineViewportStateCreateInfo viewportState({}, viewport, scissor);
    vk::PipelineRasterizationStateCreateInfo raster;
    raster.cullMode = vk::CullModeFlagBits::eNone;  // the film has two sides; props are cheap
    raster.lineWidth = 1.0f;
    const vk::PipelineMultisampleStateCreateInfo multisample({},
                                                             d.multisampled ? samples : vk::SampleCountFlagBits::e1);
    const vk::PipelineDepthStencilStateCreateInfo depthState({}, d.depthTest, d.depthWrite,
                                                             vk::CompareOp::eLessOrEqual);
    const vk::PipelineColorBlendStateCreateInfo blend({}, false, vk::LogicOp::eCopy, d.blends);
    return vk::raii::Pipeline(
        ctx->device, nullptr,
        vk::GraphicsPipelineCreateInfo({}, stages, &vertexInput, &assembly, nullptr, &viewportState, &raster,
                                       &multisample, &depthState, &blend, nullptr, *pipelineLayout, *pass, 0));
  }

  void makePipelines() {
    for (int s = 0; s <= static_cast<int>(RenderShader::CameraImageFrag); ++s) {
      const auto code = kernels::renderSpirv(static_cast<RenderShader>(s));
      modules.emplace_back(ctx->device, vk::ShaderModuleCreateInfo({}, code.size_bytes(), code.data()));
    }
    using R = RenderShader;
    props = makePipeline(
        {R::PropsVert, R::PropsFrag, vk::PrimitiveTopology::eTriangleList, true, true, {opaqueBlend()}}, opaquePass);
    cameraImage = makePipeline(
        {R::FullscreenVert, R::CameraImageFrag, vk::PrimitiveTopology::eTriangleList, true, true, {opaqueBlend()}},
        opaquePass);
    // Droplets are mostly transparent water: drawn with the film, into the same order-independent targets.
    droplets = makePipeline(
        {R::DropletsVert, R::DropletsFrag, vk::PrimitiveTopology::ePointList, true, false, transparencyBlends()},
        filmPass);
    film = makePipeline(
        {R::FilmVert, R::FilmFrag, vk::PrimitiveTopology::eTriangleList, true, false, transparencyBlends()}, filmPass);
    composite = makePipeline({R::FullscreenVert,
                              R::CompositeFrag,
                              vk::PrimitiveTopology::eTriangleList,
                              false,
                              false,
                              {opaqueBlend()},
                              false},
                             compositePass);
    skyLookup = makePipeline(
        {R::FullscreenVert, R::SkyFrag, vk::PrimitiveTopology::eTriangleList, false, false, {opaqueBlend()}, false},
        skyPass);
  }

  void makeDescriptors() {
    const std::array<vk::DescriptorPoolSize, 2> sizes{
        vk::DescriptorPoolSize(vk::DescriptorType::eStorageBuffer, 2 * 11),
        vk::DescriptorPoolSize(vk::DescriptorType::eCombinedImageSampler, 2 * 2 + 4)};
    pool = vk::raii::DescriptorPool(
        ctx->device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 3, sizes));
    const std::array<vk::DescriptorSetLayout, 3> layouts{*sceneLayout, *sceneLayout, *compositeLayout};
    vk::raii::DescriptorSets sets(ctx->device, vk::DescriptorSetAllocateInfo(*pool, layouts));
    slots[0].sceneSet = std::move(sets[0]);
    slots[1].sceneSet = std::move(sets[1]);
    compositeSet = std::move(sets[2]);
    const vk::DescriptorImageInfo images[] = {{*linearSampler, lut.view(), Layout::eShaderReadOnlyOptimal},
                                              {*linearSampler, environment.view(), Layout::eShaderReadOnlyOptimal},
                                              {*nearestSampler, opaque.view(), Layout::eShaderReadOnlyOptimal},
                                              {*nearestSampler, accum.view(), Layout::eShaderReadOnlyOptimal},
                                              {*nearestSampler, reveal.view(), Layout::eShaderReadOnlyOptimal},
                                              {*nearestSampler, sky.view(), Layout::eShaderReadOnlyOptimal}};
    using D = vk::DescriptorType;
    const vk::WriteDescriptorSet writes[] = {
        {*slots[0].sceneSet, GB_RENDER_LUT, 0, D::eCombinedImageSampler, images[0]},
        {*slots[0].sceneSet, GB_RENDER_ENVIRONMENT, 0, D::eCombinedImageSampler, images[1]},
        {*slots[1].sceneSet, GB_RENDER_LUT, 0, D::eCombinedImageSampler, images[0]},
        {*slots[1].sceneSet, GB_RENDER_ENVIRONMENT, 0, D::eCombinedImageSampler, images[1]},
        {*compositeSet, GB_COMPOSITE_OPAQUE, 0, D::eCombinedImageSampler, images[2]},
        {*compositeSet, GB_COMPOSITE_ACCUM, 0, D::eCombinedImageSampler, images[3]},
        {*compositeSet, GB_COMPOSITE_REVEAL, 0, D::eCombinedImageSampler, images[4]},
        {*compositeSet, GB_COMPOSITE_SKY, 0, D::eCombinedImageSampler, images[5]}};
    ctx->device.updateDescriptorSets(writes, {});
  }

  // A buffer holding at least `bytes`, grown (by half again) when it is too small; never none, since a
  // descriptor must name a buffer even when there is nothing in it (no droplets, a burst film).
  void reserve(DeviceBuffer& buffer, size_t bytes) {
    if (buffer.size() < std::max<size_t>(bytes, 16)) buffer = DeviceBuffer(*ctx, bytes + bytes / 2);
  }

  // The film's buffers for this frame: a copy of the stepper's own made on the device, or of the host state.
  DeviceFilm filmBuffers(const RenderFrame& frame) {
    slot().filmCopied = frame.deviceFilm != nullptr;
    if (frame.deviceFilm) {
      copyOnTheDevice(*frame.deviceFilm);
      return slotFilm(frame.deviceFilm->particleCount, frame.deviceFilm->triangleCount);
    }
    const State& s = frame.film->state;
    const std::vector<uint32_t>& tris = frame.film->topology.triangles;
    const size_t n = s.size(), bytes = n * sizeof(float);
    reserve(slot().position, 3 * bytes);
    reserve(slot().normal, 3 * bytes);
    reserve(slot().airFlow, 3 * bytes);
    reserve(slot().thickness, bytes);
    reserve(slot().triangles, tris.size() * sizeof(uint32_t));
    auto writeVec3 = [&](DeviceBuffer& b, const Vec3Array& a) {
      b.write(a.x.data(), bytes, 0);
      b.write(a.y.data(), bytes, bytes);
      b.write(a.z.data(), bytes, 2 * bytes);
    };
    writeVec3(slot().position, s.position);
    writeVec3(slot().normal, s.normal);
    writeVec3(slot().airFlow, s.airFlow);
    slot().thickness.write(s.thickness.data(), bytes);
    slot().triangles.write(tris.data(), tris.size() * sizeof(uint32_t));
    return slotFilm(static_cast<uint32_t>(n), static_cast<uint32_t>(frame.film->topology.triangleCount()));
  }
  DeviceFilm slotFilm(uint32_t particles, uint32_t triangles) const {
    const FrameSlot& f = slot();
    return {f.position.handle(), f.normal.handle(), f.thickness.handle(), f.airFlow.handle(), f.triangles.handle(),
            particles,           triangles};
  }

  // The Vulkan stepper's film copied into this frame's buffers on the device, waited for: the caller may then step
  // again, writing the stepper's buffers, while the frame is drawn from the copy. The copy costs the device one pass
  // over the film's arrays; without it the host would wait for the whole drawing before the next step. On a queue
  // that runs submissions in turn (lavapipe's) the copy itself follows the frame submitted before.
  void copyOnTheDevice(const DeviceFilm& f) {
    const vk::DeviceSize bytes = static_cast<vk::DeviceSize>(f.particleCount) * sizeof(float);
    struct Copy {
      vk::Buffer from;
      DeviceBuffer& to;
      vk::DeviceSize bytes;
    };
    const Copy copies[] = {{f.position, slot().position, 3 * bytes},
                           {f.normal, slot().normal, 3 * bytes},
                           {f.airFlow, slot().airFlow, 3 * bytes},
                           {f.thickness, slot().thickness, bytes},
                           {f.triangles, slot().triangles, 3ull * f.triangleCount * sizeof(uint32_t)}};
    const vk::raii::CommandBuffer& cb = slot().snapshotCommands;
    cb.reset();
    cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    for (const Copy& c : copies) {
      reserve(c.to, c.bytes);
      if (c.bytes > 0) cb.copyBuffer(c.from, c.to.handle(), vk::BufferCopy(0, 0, c.bytes));
    }
    cb.end();
    ctx->submitAndWait(cb);
  }

  void uploadPropsAndDroplets(const RenderFrame& frame) {
    const std::vector<float> mesh = buildProps(frame.wireFrame, frame.film);
    reserve(slot().propsMesh, mesh.size() * sizeof(float));
    slot().propsMesh.write(mesh.data(), mesh.size() * sizeof(float));
    slot().propsVertices = static_cast<uint32_t>(mesh.size() / kPropsVertexFloats);
    const std::vector<float> drops =
        frame.aerosol ? packDroplets(*frame.aerosol, frame.aerosolLifetime) : std::vector<float>();
    reserve(slot().dropletBuffer, drops.size() * sizeof(float));
    slot().dropletBuffer.write(drops.data(), drops.size() * sizeof(float));
    slot().dropletCount = static_cast<uint32_t>(drops.size() / 4);
  }

  // The film's swirls (host/film_swirls.h), for the interference colouring only: the diagnostic colourings show
  // the simulated thickness as it is.
  bool uploadVariation(const RenderFrame& frame) {
    if (options.colouring != Colouring::Interference || swirls.sigma() <= 0.0f) {
      reserve(slot().variation, 0);  // bound, not read
      return false;
    }
    const std::vector<float>& factors = swirls.update(frame.film->state);
    reserve(slot().variation, factors.size() * sizeof(float));
    slot().variation.write(factors.data(), factors.size() * sizeof(float));
    return true;
  }

  // The mirror view's camera image, for the opaque pass to draw (nothing without one).
  void uploadCameraImage(const RenderFrame& frame) {
    const CameraImage* image = frame.mirror ? frame.cameraImage : nullptr;
    const size_t pixels = image ? image->rgba.size() : 0;
    reserve(slot().cameraColour, pixels * sizeof(uint32_t));  // bound, not read, without an image
    reserve(slot().cameraDepth, pixels * sizeof(float));
    slot().drawsCameraImage = pixels > 0 && image->depth.size() == pixels;
    if (!slot().drawsCameraImage) return;
    slot().cameraColour.write(image->rgba.data(), pixels * sizeof(uint32_t));
    slot().cameraDepth.write(image->depth.data(), pixels * sizeof(float));
  }

  // The frame's view: the orbit camera, or the depth camera's in the mirror view.
  struct View {
    Eigen::Matrix4f viewProjection, skyRays;
    Vec3 eye;
    float pointScale;
  };
  View viewOf(const RenderFrame& frame) const {
    const float aspect = static_cast<float>(extent.width) / static_cast<float>(extent.height);
    if (frame.mirror)
      return {frame.mirror->viewProjection(aspect), frame.mirror->skyRays(aspect), frame.mirror->eye(),
              frame.mirror->pointScale(static_cast<int>(extent.height))};
    return {frame.camera.viewProjection(aspect), frame.camera.skyRays(aspect), frame.camera.position(),
            0.5f * static_cast<float>(extent.height) / std::tan(0.5f * frame.camera.fovY)};
  }

  void uploadUniforms(const RenderFrame& frame, const View& view, uint32_t particles, bool varied) {
    RenderUniforms u{};
    std::memcpy(u.viewProjection.m, view.viewProjection.data(), sizeof u.viewProjection.m);
    std::memcpy(u.skyRays.m, view.skyRays.data(), sizeof u.skyRays.m);
    const Vec3& eye = view.eye;
    u.cameraPosition = {eye.x(), eye.y(), eye.z(), 1.0f};
    u.keyLight = {keyLight.x(), keyLight.y(), keyLight.z(), keyStrength};
    u.horizon = {horizon.x(), horizon.y(), horizon.z(), hazeDistance};
    u.skyIrradiance = {ambient[0].x(), ambient[0].y(), ambient[0].z(), 0.0f};
    u.groundIrradiance = {ambient[1].x(), ambient[1].y(), ambient[1].z(), 0.0f};
    u.particles = particles;
    u.colouring = static_cast<uint32_t>(options.colouring);
    u.thickColour = options.thickColour;
    u.airFlowColour = options.airFlowColour;
    u.exposure = options.exposure;
    u.pointScale = view.pointScale;
    if (frame.mirror) {
      const Eigen::Vector4f image =
          frame.mirror->imageOfPicture(static_cast<int>(extent.width), static_cast<int>(extent.height));
      const Eigen::Vector2f distance = frame.mirror->depthOfDistance();
      u.cameraImage = {image.x(), image.y(), image.z(), image.w()};
      const CameraImage* c = frame.cameraImage;
      u.cameraDepth = {distance.x(), distance.y(), c ? static_cast<float>(c->width) : 0.0f,
                       c ? static_cast<float>(c->height) : 0.0f};
    }
    u.dropletRadius = options.dropletRadius;
    u.thicknessVariation = varied ? 1u : 0u;
    // Drainage approaches the black film's thickness from above (stages.h, filmFlowLimit): film within a quarter of
    // it has made the jump to black film.
    u.blackFilmThickness = 1.25f * frame.blackFilmThickness;
    u.minTubePixels = options.minTubePixels;
    slot().uniforms.write(&u, sizeof u);
  }

  void bindSceneBuffers(const DeviceFilm& f) {
    auto info = [](vk::Buffer b) { return vk::DescriptorBufferInfo(b, 0, VK_WHOLE_SIZE); };
    const std::pair<uint32_t, vk::DescriptorBufferInfo> buffers[] = {
        {GB_RENDER_UNIFORMS, info(slot().uniforms.handle())},
        {GB_RENDER_POSITION, info(f.position)},
        {GB_RENDER_NORMAL, info(f.normal)},
        {GB_RENDER_THICKNESS, info(f.thickness)},
        {GB_RENDER_AIR_FLOW, info(f.airFlow)},
        {GB_RENDER_TRIANGLES, info(f.triangles)},
        {GB_RENDER_MESH, info(slot().propsMesh.handle())},
        {GB_RENDER_DROPLETS, info(slot().dropletBuffer.handle())},
        {GB_RENDER_VARIATION, info(slot().variation.handle())},
        {GB_RENDER_CAMERA_COLOUR, info(slot().cameraColour.handle())},
        {GB_RENDER_CAMERA_DEPTH, info(slot().cameraDepth.handle())}};
    std::vector<vk::WriteDescriptorSet> writes;
    for (const auto& [binding, buffer] : buffers)
      writes.emplace_back(*slot().sceneSet, binding, 0, vk::DescriptorType::eStorageBuffer, nullptr, buffer);
    ctx->device.updateDescriptorSets(writes, {});
  }

  void record(const DeviceFilm& f, bool drawSky, bool readPixels, const AfterRender& after) {
    const vk::raii::CommandBuffer& cb = slot().commands;
    cb.reset();
    cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    const vk::QueryPool timestamps = *slot().timestamps;
    if (timestamps) {
      cb.resetQueryPool(timestamps, 0, 2);
      cb.writeTimestamp(Stage::eTopOfPipe, timestamps, 0);
    }
    if (slot().filmCopied) {  // the copy's writes, seen by the film's index and vertex reads
      const vk::MemoryBarrier copied(Access::eTransferWrite, Access::eIndexRead | Access::eShaderRead);
      cb.pipelineBarrier(Stage::eTransfer, Stage::eVertexInput | Stage::eVertexShader, {}, copied, {}, {});
    }
    const vk::Rect2D area({0, 0}, extent);
    const std::array<vk::DescriptorSet, 2> sets{*slot().sceneSet, *compositeSet};
    cb.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipelineLayout, 0, sets, {});

    // Alpha 0: no prop here, the resolve shows the environment.
    const std::array<vk::ClearValue, 3> opaqueClear{vk::ClearColorValue(std::array<float, 4>{0, 0, 0, 0}),
                                                    vk::ClearDepthStencilValue(1.0f, 0), vk::ClearValue()};
    cb.beginRenderPass(vk::RenderPassBeginInfo(*opaquePass, *opaqueTarget, area, opaqueClear),
                       vk::SubpassContents::eInline);
    cb.bindPipeline(vk::PipelineBindPoint::eGraphics, *props);
    cb.draw(slot().propsVertices, 1, 0, 0);
    if (slot().drawsCameraImage) {
      cb.bindPipeline(vk::PipelineBindPoint::eGraphics, *cameraImage);
      cb.draw(3, 1, 0, 0);
    }
    cb.endRenderPass();

    const std::array<vk::ClearValue, 5> filmClear{vk::ClearColorValue(std::array<float, 4>{0, 0, 0, 0}),
                                                  vk::ClearColorValue(std::array<float, 4>{0, 0, 0, 0}),
                                                  vk::ClearValue(), vk::ClearValue(), vk::ClearValue()};
    cb.beginRenderPass(vk::RenderPassBeginInfo(*filmPass, *filmTarget, area, filmClear), vk::SubpassContents::eInline);
    if (f.triangleCount > 0) {
      cb.bindPipeline(vk::PipelineBindPoint::eGraphics, *film);
      cb.bindIndexBuffer(f.triangles, 0, vk::IndexType::eUint32);
      cb.drawIndexed(3 * f.triangleCount, 1, 0, 0, 0);
    }
    if (slot().dropletCount > 0) {
      cb.bindPipeline(vk::PipelineBindPoint::eGraphics, *droplets);
      cb.draw(slot().dropletCount, 1, 0, 0);
    }
    cb.endRenderPass();

    if (drawSky) {
      cb.beginRenderPass(vk::RenderPassBeginInfo(*skyPass, *skyTarget, area, {}), vk::SubpassContents::eInline);
      cb.bindPipeline(vk::PipelineBindPoint::eGraphics, *skyLookup);
      cb.draw(3, 1, 0, 0);
      cb.endRenderPass();
    }
    cb.beginRenderPass(vk::RenderPassBeginInfo(*compositePass, *compositeTarget, area, {}),
                       vk::SubpassContents::eInline);
    cb.bindPipeline(vk::PipelineBindPoint::eGraphics, *composite);
    cb.draw(3, 1, 0, 0);
    cb.endRenderPass();

    if (readPixels) {
      cb.copyImageToBuffer(output.handle(), Layout::eTransferSrcOptimal, slot().readback.handle(),
                           vk::BufferImageCopy(0, 0, 0, {vk::ImageAspectFlagBits::eColor, 0, 0, 1}, {0, 0, 0},
                                               vk::Extent3D(extent.width, extent.height, 1)));
      const vk::MemoryBarrier toHost(Access::eTransferWrite, Access::eHostRead);
      cb.pipelineBarrier(Stage::eTransfer, Stage::eHost, {}, toHost, {}, {});
    }
    if (after) after(cb, output.handle());
    if (timestamps) cb.writeTimestamp(Stage::eBottomOfPipe, timestamps, 1);
    cb.end();
  }
};

double renderTargetBytes(int width, int height, int samples) {
  const double pixels = static_cast<double>(width) * height;
  const double resolved = 8 + 8 + 2 + 4;                       // opaque, accum, reveal, output
  const double perSample = 4 + (samples > 1 ? 8 + 8 + 2 : 0);  // depth, and the multisampled colours
  const double hostRows = 2 * 4;                               // two frames' read-back rows
  return pixels * (resolved + perSample * samples + hostRows);
}

std::string renderSizeProblem(int width, int height, int samples, int largestSide, double heapBytes,
                              const std::string& device) {
  const int side = std::min(largestSide, kMaxRenderSide);
  char text[300];
  if (width < 16 || height < 16 || width > side || height > side) {
    std::snprintf(text, sizeof text, "render size %dx%d is outside 16..%d pixels on %s (--width, --height)", width,
                  height, side, device.c_str());
    return text;
  }
  const double bytes = renderTargetBytes(width, height, samples);
  if (bytes <= heapBytes / 4) return {};
  std::snprintf(text, sizeof text,
                "a %dx%d image at %d sample%s per pixel takes %.1f GB of render targets, more than a quarter of the "
                "%.1f GB of %s: give a smaller --width and --height",
                width, height, samples, samples == 1 ? "" : "s", bytes / 1e9, heapBytes / 1e9, device.c_str());
  return text;
}

Renderer::Renderer(std::shared_ptr<const VulkanContext> context, const RenderOptions& options,
                   const EnvironmentImage& environment)
    : impl_(std::make_unique<Impl>(std::move(context), options, environment)) {}

Renderer::~Renderer() = default;

void Renderer::render(const RenderFrame& frame, bool readback, const AfterRender& after) {
  submit(frame, readback, after);
  wait();
}

Renderer::Ticket Renderer::submit(const RenderFrame& frame, bool readback, const AfterRender& after) {
  Impl& m = *impl_;
  if (!frame.film) throw std::invalid_argument("Renderer::submit: no film");
  m.current = 1 - m.current;
  m.wait(m.slot());  // the frame two submits ago: its buffers and command buffer are reused
  const DeviceFilm film = m.filmBuffers(frame);
  m.uploadPropsAndDroplets(frame);
  const bool varied = m.uploadVariation(frame);
  m.uploadCameraImage(frame);
  const Impl::View view = m.viewOf(frame);
  m.uploadUniforms(frame, view, film.particleCount, varied);
  m.bindSceneBuffers(film);
  // The sky is drawn again only when the view turns or zooms (or the size changes): on lavapipe a full-screen
  // environment lookup costs a seventh of a main-job frame, and the framing often holds its direction.
  Impl::SkyView sky{{}, m.extent.width, m.extent.height};
  std::memcpy(sky.rays.data(), view.skyRays.data(), sizeof sky.rays);
  const bool drawSky = m.skyDrawnFor != sky;
  m.skyDrawnFor = sky;
  m.record(film, drawSky, readback, after);
  m.ctx->submit(m.slot().commands, m.slot().done);
  m.slot().inFlight = true;
  return m.slot().ticket = ++m.tickets;
}

void Renderer::wait() { impl_->waitForAll(); }

std::vector<Renderer::BusyInterval> Renderer::takeDrawnIntervals() { return std::exchange(impl_->drawn, {}); }

std::vector<uint8_t> Renderer::readPixels() { return readPixels(impl_->slot().ticket); }

std::vector<uint8_t> Renderer::readPixels(Ticket frame) {
  Impl& m = *impl_;
  const auto held = std::find_if(m.slots.begin(), m.slots.end(), [&](const auto& f) { return f.ticket == frame; });
  if (held == m.slots.end())
    throw std::logic_error("Renderer::readPixels: frame " + std::to_string(frame) +
                           " is no longer held (two frames are kept: read a frame before submitting two more)");
  m.wait(*held);
  const size_t pixels = static_cast<size_t>(m.extent.width) * m.extent.height;
  std::vector<uint8_t> rgba(4 * pixels), rgb(3 * pixels);
  held->readback.read(rgba.data(), rgba.size());
  for (size_t i = 0; i < pixels; ++i)
    for (size_t c = 0; c < 3; ++c) rgb[3 * i + c] = rgba[4 * i + c];
  return rgb;
}

void Renderer::resize(int width, int height) {
  if (width != impl_->options.width || height != impl_->options.height) impl_->resize(width, height);
}

void Renderer::setColouring(Colouring colouring) { impl_->options.colouring = colouring; }
const RenderOptions& Renderer::options() const { return impl_->options; }
const VulkanContext& Renderer::context() const { return *impl_->ctx; }

}  // namespace gb
