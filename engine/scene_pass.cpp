// The OIT scene pass: render pass, pipelines, targets, mesh cache and per-frame geometry.
#include "engine/scene_pass.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace ps::engine {

namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr VkFormat kAccumFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kRevealFormat = VK_FORMAT_R16_SFLOAT;

// Mirrors shaders/push.glsl.
struct PushConstants {
  glm::mat4 transform{1.f};
  glm::vec4 color{1.f};
  glm::vec4 eye{0.f};
  glm::vec4 forward{0.f};
  glm::vec4 params{0.f};
};
static_assert(sizeof(PushConstants) == 128);

#define PS_VK_CHECK(call, what)                                                           \
  do {                                                                                    \
    const VkResult ps_vk_result_ = (call);                                                \
    if (ps_vk_result_ != VK_SUCCESS)                                                      \
      return Status::error(std::string(what) + " failed: " + vk::result_name(ps_vk_result_)); \
  } while (0)

enum class VertexKind { mesh, color, none };
enum class BlendKind { opaque, oit, composite };

struct PipelineDesc {
  const char* vert;
  const char* frag;
  uint32_t subpass;
  VertexKind vertices;
  BlendKind blend;
  bool depth_test;
  bool depth_write;
  bool cull_back = false;
};

Result<vk::Pipeline> make_pipeline(const vk::Context& ctx, VkRenderPass pass,
                                   VkPipelineLayout layout, const PipelineDesc& d) {
  auto vs = ctx.load_shader(std::string(d.vert) + ".spv");
  if (!vs) return vs.status();
  auto fs = ctx.load_shader(std::string(d.frag) + ".spv");
  if (!fs) return fs.status();
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  for (auto& s : stages) {
    s.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    s.pName = "main";
  }
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs->get();
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs->get();

  // === Vertex input
  VkVertexInputBindingDescription binding{};
  std::array<VkVertexInputAttributeDescription, 2> attrs{};
  VkPipelineVertexInputStateCreateInfo vi{};
  vi.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  if (d.vertices != VertexKind::none) {
    binding.binding = 0;
    binding.inputRate = VK_VERTEX_INPUT_RATE_VERTEX;
    if (d.vertices == VertexKind::mesh) {
      binding.stride = sizeof(MeshVertex);
      attrs[0] = {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, pos)};
      attrs[1] = {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, normal)};
    } else {
      binding.stride = sizeof(ColorVertex);
      attrs[0] = {0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(ColorVertex, pos)};
      attrs[1] = {1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(ColorVertex, color)};
    }
    vi.vertexBindingDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &binding;
    vi.vertexAttributeDescriptionCount = 2;
    vi.pVertexAttributeDescriptions = attrs.data();
  }
  VkPipelineInputAssemblyStateCreateInfo ia{};
  ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;

  VkPipelineViewportStateCreateInfo vp{};
  vp.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  vp.viewportCount = 1;
  vp.scissorCount = 1;

  VkPipelineRasterizationStateCreateInfo rs{};
  rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  // Meshes are lit two-sided and planes and ribbons face both ways, so nothing is culled except
  // opaque closed meshes. Faces are counter-clockwise seen from outside; Vulkan's facing
  // formula (a = -1/2 sum x_i y_{i+1} - x_{i+1} y_i in y-down framebuffer coordinates) already
  // absorbs the y flip of our projection, so counter-clockwise stays front-facing.
  rs.cullMode = d.cull_back ? VkCullModeFlags{VK_CULL_MODE_BACK_BIT} : VkCullModeFlags{VK_CULL_MODE_NONE};
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.f;

  VkPipelineMultisampleStateCreateInfo ms{};
  ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

  VkPipelineDepthStencilStateCreateInfo ds{};
  ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  ds.depthTestEnable = d.depth_test ? VK_TRUE : VK_FALSE;
  ds.depthWriteEnable = d.depth_write ? VK_TRUE : VK_FALSE;
  ds.depthCompareOp = VK_COMPARE_OP_LESS;

  // === Blending
  std::array<VkPipelineColorBlendAttachmentState, 2> blend{};
  uint32_t blend_count = 1;
  const VkColorComponentFlags rgba = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                     VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  switch (d.blend) {
    case BlendKind::opaque:
      blend[0].colorWriteMask = rgba;
      break;
    case BlendKind::oit:
      blend_count = 2;
      // Accumulation: sum of premultiplied, weighted colours and weighted alphas.
      blend[0] = {VK_TRUE, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE, VK_BLEND_OP_ADD,
                  VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE, VK_BLEND_OP_ADD, rgba};
      // Revealage: product of (1 - alpha).
      blend[1] = {VK_TRUE, VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR,
                  VK_BLEND_OP_ADD, VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                  VK_BLEND_OP_ADD, VK_COLOR_COMPONENT_R_BIT};
      break;
    case BlendKind::composite:
      blend[0] = {VK_TRUE, VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                  VK_BLEND_OP_ADD, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                  VK_BLEND_OP_ADD, rgba};
      break;
  }
  VkPipelineColorBlendStateCreateInfo cb{};
  cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  cb.attachmentCount = blend_count;
  cb.pAttachments = blend.data();

  const std::array<VkDynamicState, 2> dyn{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{};
  dy.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dy.dynamicStateCount = static_cast<uint32_t>(dyn.size());
  dy.pDynamicStates = dyn.data();

  VkGraphicsPipelineCreateInfo pci{};
  pci.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  pci.stageCount = 2;
  pci.pStages = stages.data();
  pci.pVertexInputState = &vi;
  pci.pInputAssemblyState = &ia;
  pci.pViewportState = &vp;
  pci.pRasterizationState = &rs;
  pci.pMultisampleState = &ms;
  pci.pDepthStencilState = d.subpass == 2 ? nullptr : &ds;  // the composite has no depth
  pci.pColorBlendState = &cb;
  pci.pDynamicState = &dy;
  pci.layout = layout;
  pci.renderPass = pass;
  pci.subpass = d.subpass;
  VkPipeline p = VK_NULL_HANDLE;
  if (const VkResult r =
          vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &pci, nullptr, &p);
      r != VK_SUCCESS)
    return Result<vk::Pipeline>::error(std::string("pipeline ") + d.vert + "/" + d.frag +
                                       ": " + vk::result_name(r));
  return vk::Pipeline(ctx.device(), p);
}

Result<vk::RenderPass> make_render_pass(VkDevice device) {
  // === Attachments: 0 colour, 1 depth, 2 accumulation, 3 revealage
  std::array<VkAttachmentDescription, 4> att{};
  for (auto& a : att) {
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  }
  att[0].format = kColorFormat;
  att[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  att[0].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  att[1].format = kDepthFormat;
  att[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  att[2].format = kAccumFormat;
  att[2].finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  att[3].format = kRevealFormat;
  att[3].finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

  const VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  const std::array<VkAttachmentReference, 2> oit_refs{
      VkAttachmentReference{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
      VkAttachmentReference{3, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
  const std::array<VkAttachmentReference, 2> input_refs{
      VkAttachmentReference{2, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      VkAttachmentReference{3, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
  const uint32_t preserve_color = 0;

  std::array<VkSubpassDescription, 3> sub{};
  for (auto& s : sub) s.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub[0].colorAttachmentCount = 1;
  sub[0].pColorAttachments = &color_ref;
  sub[0].pDepthStencilAttachment = &depth_ref;
  sub[1].colorAttachmentCount = 2;
  sub[1].pColorAttachments = oit_refs.data();
  sub[1].pDepthStencilAttachment = &depth_ref;
  sub[1].preserveAttachmentCount = 1;
  sub[1].pPreserveAttachments = &preserve_color;
  sub[2].colorAttachmentCount = 1;
  sub[2].pColorAttachments = &color_ref;
  sub[2].inputAttachmentCount = 2;
  sub[2].pInputAttachments = input_refs.data();

  // === Dependencies
  const VkPipelineStageFlags frag_tests =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkPipelineStageFlags color_out = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  std::array<VkSubpassDependency, 5> dep{};
  // Previous frame (read-back / blit, attachment writes) before this frame's clears.
  dep[0] = {VK_SUBPASS_EXTERNAL, 0,
            VK_PIPELINE_STAGE_TRANSFER_BIT | color_out | frag_tests,
            color_out | frag_tests,
            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
            VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
            0};
  // Opaque depth before translucent depth tests (and the OIT targets' clears).
  dep[1] = {0, 1, frag_tests | color_out, frag_tests | color_out,
            VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
            VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
                VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
            VK_DEPENDENCY_BY_REGION_BIT};
  // Accumulation / revealage writes before the composite reads them.
  dep[2] = {1, 2, color_out, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_INPUT_ATTACHMENT_READ_BIT,
            VK_DEPENDENCY_BY_REGION_BIT};
  // Opaque colour before the composite blends over it.
  dep[3] = {0, 2, color_out, color_out, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
            VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
            VK_DEPENDENCY_BY_REGION_BIT};
  // Final colour before the read-back copy or blit.
  dep[4] = {2, VK_SUBPASS_EXTERNAL, color_out, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, 0};

  VkRenderPassCreateInfo rpci{};
  rpci.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  rpci.attachmentCount = static_cast<uint32_t>(att.size());
  rpci.pAttachments = att.data();
  rpci.subpassCount = static_cast<uint32_t>(sub.size());
  rpci.pSubpasses = sub.data();
  rpci.dependencyCount = static_cast<uint32_t>(dep.size());
  rpci.pDependencies = dep.data();
  VkRenderPass rp = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateRenderPass(device, &rpci, nullptr, &rp); r != VK_SUCCESS)
    return Result<vk::RenderPass>::error("vkCreateRenderPass failed: " + vk::result_name(r));
  return vk::RenderPass(device, rp);
}

VkDeviceSize next_capacity(VkDeviceSize need) {
  VkDeviceSize c = 64 * 1024;
  while (c < need) c *= 2;
  return c;
}

}  // namespace

Result<std::unique_ptr<ScenePass>> ScenePass::create(const vk::Context& ctx, VkExtent2D extent) {
  std::unique_ptr<ScenePass> p(new ScenePass(ctx));
  const VkDevice dev = ctx.device();
  auto rp = make_render_pass(dev);
  if (!rp) return rp.status();
  p->render_pass_ = std::move(*rp);

  // === Descriptor set for the composite's input attachments
  std::array<VkDescriptorSetLayoutBinding, 2> bindings{};
  for (uint32_t i = 0; i < 2; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 1, VK_SHADER_STAGE_FRAGMENT_BIT,
                   nullptr};
  VkDescriptorSetLayoutCreateInfo dslci{};
  dslci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  dslci.bindingCount = 2;
  dslci.pBindings = bindings.data();
  VkDescriptorSetLayout dsl = VK_NULL_HANDLE;
  PS_VK_CHECK(vkCreateDescriptorSetLayout(dev, &dslci, nullptr, &dsl),
              "vkCreateDescriptorSetLayout");
  p->set_layout_ = vk::DescriptorSetLayout(dev, dsl);

  VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(PushConstants)};
  VkPipelineLayoutCreateInfo plci{};
  plci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  plci.setLayoutCount = 1;
  plci.pSetLayouts = &dsl;
  plci.pushConstantRangeCount = 1;
  plci.pPushConstantRanges = &push;
  VkPipelineLayout pl = VK_NULL_HANDLE;
  PS_VK_CHECK(vkCreatePipelineLayout(dev, &plci, nullptr, &pl), "vkCreatePipelineLayout");
  p->pipeline_layout_ = vk::PipelineLayout(dev, pl);

  auto pool = ctx.create_descriptor_pool(VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 2, 1);
  if (!pool) return pool.status();
  p->descriptor_pool_ = std::move(*pool);
  const VkDescriptorPool dp = p->descriptor_pool_.get();
  VkDescriptorSetAllocateInfo dsai{};
  dsai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  dsai.descriptorPool = dp;
  dsai.descriptorSetCount = 1;
  dsai.pSetLayouts = &dsl;
  VkDescriptorSet set = VK_NULL_HANDLE;
  PS_VK_CHECK(vkAllocateDescriptorSets(dev, &dsai, &set), "vkAllocateDescriptorSets");
  p->composite_set_ = vk::DescriptorSet(dev, dp, set);

  if (auto st = p->create_pipelines(); !st) return st;
  if (auto st = p->resize(extent); !st) return st;
  return p;
}

Status ScenePass::create_pipelines() {
  const VkRenderPass rp = render_pass_.get();
  const VkPipelineLayout pl = pipeline_layout_.get();
  struct Entry {
    vk::Pipeline* target;
    PipelineDesc desc;
  };
  const std::array<Entry, 9> entries{{
      {&mesh_[0][0], {"mesh.vert", "mesh_opaque.frag", 0, VertexKind::mesh, BlendKind::opaque, true, true}},
      {&mesh_[0][1], {"mesh.vert", "mesh_opaque.frag", 0, VertexKind::mesh, BlendKind::opaque, true, true, true}},
      {&mesh_[0][2], {"mesh.vert", "mesh_oit.frag", 1, VertexKind::mesh, BlendKind::oit, true, false}},
      {&mesh_[1][0], {"mesh_wire.vert", "mesh_opaque_wire.frag", 0, VertexKind::mesh, BlendKind::opaque, true, true}},
      {&mesh_[1][1], {"mesh_wire.vert", "mesh_opaque_wire.frag", 0, VertexKind::mesh, BlendKind::opaque, true, true, true}},
      {&mesh_[1][2], {"mesh_wire.vert", "mesh_oit_wire.frag", 1, VertexKind::mesh, BlendKind::oit, true, false}},
      {&color_opaque_, {"color.vert", "color_opaque.frag", 0, VertexKind::color, BlendKind::opaque, true, true}},
      {&color_oit_, {"color.vert", "color_oit.frag", 1, VertexKind::color, BlendKind::oit, true, false}},
      {&composite_, {"composite.vert", "composite.frag", 2, VertexKind::none, BlendKind::composite, false, false}},
  }};
  for (const auto& e : entries) {
    auto p = make_pipeline(ctx_, rp, pl, e.desc);
    if (!p) return p.status();
    *e.target = std::move(*p);
  }
  return Status::ok();
}

Status ScenePass::resize(VkExtent2D extent) {
  if (extent.width == targets_.extent.width && extent.height == targets_.extent.height &&
      targets_.framebuffer)
    return Status::ok();
  Targets t;
  t.extent = extent;
  auto color = ctx_.create_image(extent, kColorFormat,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                 VK_IMAGE_ASPECT_COLOR_BIT);
  if (!color) return color.status();
  t.color = std::move(*color);
  auto depth = ctx_.create_image(extent, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                 VK_IMAGE_ASPECT_DEPTH_BIT);
  if (!depth) return depth.status();
  t.depth = std::move(*depth);
  const VkImageUsageFlags oit_usage =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
  auto accum = ctx_.create_image(extent, kAccumFormat, oit_usage, VK_IMAGE_ASPECT_COLOR_BIT);
  if (!accum) return accum.status();
  t.accum = std::move(*accum);
  auto reveal = ctx_.create_image(extent, kRevealFormat, oit_usage, VK_IMAGE_ASPECT_COLOR_BIT);
  if (!reveal) return reveal.status();
  t.reveal = std::move(*reveal);

  const std::array<VkImageView, 4> views{t.color.view.get(), t.depth.view.get(),
                                         t.accum.view.get(), t.reveal.view.get()};
  VkFramebufferCreateInfo fci{};
  fci.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  fci.renderPass = render_pass_.get();
  fci.attachmentCount = static_cast<uint32_t>(views.size());
  fci.pAttachments = views.data();
  fci.width = extent.width;
  fci.height = extent.height;
  fci.layers = 1;
  VkFramebuffer fb = VK_NULL_HANDLE;
  PS_VK_CHECK(vkCreateFramebuffer(ctx_.device(), &fci, nullptr, &fb), "vkCreateFramebuffer");
  t.framebuffer = vk::Framebuffer(ctx_.device(), fb);

  std::array<VkDescriptorImageInfo, 2> infos{
      VkDescriptorImageInfo{VK_NULL_HANDLE, t.accum.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      VkDescriptorImageInfo{VK_NULL_HANDLE, t.reveal.view.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
  std::array<VkWriteDescriptorSet, 2> writes{};
  for (uint32_t i = 0; i < 2; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = composite_set_.get();
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
    writes[i].pImageInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device(), 2, writes.data(), 0, nullptr);
  targets_ = std::move(t);
  return Status::ok();
}

Status ScenePass::update_mesh(GpuMesh& slot, const MeshVisual& m) {
  const uint64_t fp = mesh_fingerprint(m.mesh);
  if (slot.valid && slot.fingerprint == fp && slot.wireframe == m.wireframe) return Status::ok();
  slot.valid = false;
  const MeshBuffers data = prepare_mesh(m.mesh, m.wireframe);
  if (data.indices.empty()) {
    slot.index_count = 0;
  } else {
    const VkDeviceSize vbytes = data.vertices.size() * sizeof(MeshVertex);
    const VkDeviceSize ibytes = data.indices.size() * sizeof(uint32_t);
    // Reuse the buffers when the new data fits.
    if (!slot.vertices.buffer || slot.vertices.size < vbytes) {
      auto vb = ctx_.create_buffer(next_capacity(vbytes), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, true);
      if (!vb) return vb.status();
      slot.vertices = std::move(*vb);
    }
    if (!slot.indices.buffer || slot.indices.size < ibytes) {
      auto ib = ctx_.create_buffer(next_capacity(ibytes), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, true);
      if (!ib) return ib.status();
      slot.indices = std::move(*ib);
    }
    std::memcpy(slot.vertices.mapped, data.vertices.data(), vbytes);
    std::memcpy(slot.indices.mapped, data.indices.data(), ibytes);
    slot.index_count = static_cast<uint32_t>(data.indices.size());
  }
  slot.closed = is_closed_and_outward(m.mesh);
  slot.box = ps::bounding_box(m.mesh.vertices);
  slot.fingerprint = fp;
  slot.wireframe = m.wireframe;
  slot.valid = true;
  ++mesh_uploads_;
  return Status::ok();
}

Status ScenePass::prepare(const Scene& scene) {
  if (auto st = validate_scene(scene); !st) return st;
  if (auto st = resize({static_cast<uint32_t>(scene.camera.width),
                        static_cast<uint32_t>(scene.camera.height)});
      !st)
    return st;
  camera_ = scene.camera;
  background_ = scene.background;
  view_proj_ = vulkan_view_projection(scene.camera);

  solid_draw_ = {};
  preview_draw_ = {};
  if (scene.solid) {
    if (auto st = update_mesh(solid_, *scene.solid); !st) return st;
    solid_draw_ = {solid_.index_count > 0, scene.solid->color, scene.solid->wireframe};
  }
  if (scene.preview) {
    if (auto st = update_mesh(preview_, *scene.preview); !st) return st;
    preview_draw_ = {preview_.index_count > 0 && scene.preview->color.a > 0.f,
                     scene.preview->color, scene.preview->wireframe};
  }

  // === Per-frame coloured geometry, packed into one host-visible buffer
  const FrameGeometry fg = build_frame_geometry(scene);
  // === Composite scissor: the screen bounds of everything translucent. The full-screen
  // composite costs lavapipe about 12 ms of CPU per 1280x800 frame, so it pays to shrink it.
  PixelBounds bounds = fg.translucent_bounds;
  if (preview_draw_.enabled) {
    const ps::Box3& b = preview_.box;
    for (int k = 0; k < 8; ++k) {
      const glm::vec4 corner(float(k & 1 ? b.max.x() : b.min.x()), float(k & 2 ? b.max.y() : b.min.y()),
                             float(k & 4 ? b.max.z() : b.min.z()), 1.f);
      bounds.add_clip(view_proj_ * corner);
    }
  }
  composite_rect_ = bounds.empty()
                        ? VkRect2D{{0, 0}, {0, 0}}
                        : VkRect2D{{bounds.x0, bounds.y0},
                                   {static_cast<uint32_t>(bounds.x1 - bounds.x0),
                                    static_cast<uint32_t>(bounds.y1 - bounds.y0)}};
  fills_count_ = fg.plane_fills.size();
  opaque_ribbons_count_ = fg.opaque_ribbons.size();
  translucent_ribbons_count_ = fg.translucent_ribbons.size();
  const VkDeviceSize stride = sizeof(ColorVertex);
  fills_offset_ = 0;
  opaque_ribbons_offset_ = fills_offset_ + fills_count_ * stride;
  translucent_ribbons_offset_ = opaque_ribbons_offset_ + opaque_ribbons_count_ * stride;
  const VkDeviceSize total = translucent_ribbons_offset_ + translucent_ribbons_count_ * stride;
  if (total > 0) {
    if (!dynamic_.buffer || dynamic_.size < total) {
      auto b = ctx_.create_buffer(next_capacity(total), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, true);
      if (!b) return b.status();
      dynamic_ = std::move(*b);
    }
    auto* base = static_cast<char*>(dynamic_.mapped);
    const auto copy = [&](VkDeviceSize off, const std::vector<ColorVertex>& v) {
      if (!v.empty()) std::memcpy(base + off, v.data(), v.size() * stride);
    };
    copy(fills_offset_, fg.plane_fills);
    copy(opaque_ribbons_offset_, fg.opaque_ribbons);
    copy(translucent_ribbons_offset_, fg.translucent_ribbons);
  }
  return Status::ok();
}

void ScenePass::draw_mesh(VkCommandBuffer cmd, VkPipeline pipeline, const GpuMesh& m,
                          const Draw& d) const {
  PushConstants pc;
  pc.transform = view_proj_;
  pc.color = {d.color.r, d.color.g, d.color.b, d.color.a};
  const ps::Vec3 f = (camera_.target - camera_.eye).normalized();
  pc.eye = {float(camera_.eye.x()), float(camera_.eye.y()), float(camera_.eye.z()),
            camera_.orthographic ? 0.f : 1.f};
  pc.forward = {float(f.x()), float(f.y()), float(f.z()),
                float((camera_.target - camera_.eye).norm())};
  pc.params = {0.f, float(camera_.near_plane),
               float(camera_.far_plane - camera_.near_plane), 0.f};
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  vkCmdPushConstants(cmd, pipeline_layout_.get(),
                     VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof pc, &pc);
  const VkBuffer vb = m.vertices.buffer.get();
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
  vkCmdBindIndexBuffer(cmd, m.indices.buffer.get(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(cmd, m.index_count, 1, 0, 0, 0);
}

void ScenePass::draw_colored(VkCommandBuffer cmd, VkPipeline pipeline, bool world_space,
                             VkDeviceSize offset, std::size_t count) const {
  if (count == 0) return;
  PushConstants pc;
  pc.transform = world_space ? view_proj_ : glm::mat4(1.f);
  pc.eye = {0.f, 0.f, 0.f, camera_.orthographic ? 0.f : 1.f};
  pc.forward = {0.f, 0.f, 0.f, float((camera_.target - camera_.eye).norm())};
  pc.params = {0.f, float(camera_.near_plane), float(camera_.far_plane - camera_.near_plane), 0.f};
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  vkCmdPushConstants(cmd, pipeline_layout_.get(),
                     VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof pc, &pc);
  const VkBuffer vb = dynamic_.buffer.get();
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
  vkCmdDraw(cmd, static_cast<uint32_t>(count), 1, 0, 0);
}

void ScenePass::record(VkCommandBuffer cmd) const {
  std::array<VkClearValue, 4> clears{};
  clears[0].color = {{background_.r, background_.g, background_.b, background_.a}};
  clears[1].depthStencil = {1.f, 0};
  clears[2].color = {{0.f, 0.f, 0.f, 0.f}};
  clears[3].color = {{1.f, 0.f, 0.f, 0.f}};
  VkRenderPassBeginInfo rpbi{};
  rpbi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  rpbi.renderPass = render_pass_.get();
  rpbi.framebuffer = targets_.framebuffer.get();
  rpbi.renderArea = {{0, 0}, targets_.extent};
  rpbi.clearValueCount = static_cast<uint32_t>(clears.size());
  rpbi.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &rpbi, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0.f, 0.f, float(targets_.extent.width), float(targets_.extent.height),
                            0.f, 1.f};
  const VkRect2D scissor{{0, 0}, targets_.extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);

  // === Subpass 0: opaque
  if (solid_draw_.enabled) {
    const int variant = solid_.closed && !disable_culling_ ? 1 : 0;
    draw_mesh(cmd, mesh_[solid_draw_.wireframe][variant].get(), solid_, solid_draw_);
  }
  draw_colored(cmd, color_opaque_.get(), false, opaque_ribbons_offset_, opaque_ribbons_count_);

  // === Subpass 1: translucent accumulation
  vkCmdNextSubpass(cmd, VK_SUBPASS_CONTENTS_INLINE);
  if (preview_draw_.enabled) draw_mesh(cmd, mesh_[preview_draw_.wireframe][2].get(), preview_, preview_draw_);
  draw_colored(cmd, color_oit_.get(), true, fills_offset_, fills_count_);
  draw_colored(cmd, color_oit_.get(), false, translucent_ribbons_offset_,
               translucent_ribbons_count_);

  // === Subpass 2: composite (skipped when nothing translucent was drawn)
  vkCmdNextSubpass(cmd, VK_SUBPASS_CONTENTS_INLINE);
  if (composite_rect_.extent.width > 0 && composite_rect_.extent.height > 0) {
    vkCmdSetScissor(cmd, 0, 1, &composite_rect_);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, composite_.get());
    const VkDescriptorSet set = composite_set_.get();
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_.get(), 0, 1,
                            &set, 0, nullptr);
    vkCmdDraw(cmd, 3, 1, 0, 0);
  }
  vkCmdEndRenderPass(cmd);
}

}  // namespace ps::engine
