/* SPDX-License-Identifier: Apache-2.0 */
/* vk_backend.c - the Vulkan compute backend (host/backend/backend.h): a
 * device and queue opened at the first frame, the flattened layout in
 * storage buffers (uploaded once, then only what changed), compute pipelines
 * specialised to the scene through specialization constants, and frames in
 * bounded dispatches over tiles of pixels (kernels/vulkan/).
 *
 * The shaders are the GLSL mirror of the shared maths in the portable
 * profile (kernels/vulkan/, file for file): every float operation
 * NoContraction, division and sqrt in software from integer operations, no
 * fp64. The backend adds the float-control execution modes the device
 * supports (round to nearest even, signed zeros/infs/NaNs kept, denormals
 * kept) before handing a module to the driver; with all three the oracle's
 * bits are promised (rt_vk_device_info.exact).
 *
 * Buffers live in host-visible, coherent memory (device-local too where the
 * device has such memory: integrated GPUs, lavapipe, resizable BAR), mapped
 * once: an upload is a copy into the mapping. */
#include "vulkan/vk_backend.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "backend/upload_plan.h"
#include "base/clock.h"
#include "base/error.h"
#include "rt_interface.h"
#include "rt_shade.h"
#include "vulkan/vk_internal.h"
#include "vulkan/vk_pipeline_cache.h"

/* Generated from kernels/vulkan/ at build time (cmake/embed_spirv.cmake). */
extern const uint32_t rt_vk_spirv_rt_vk_main[], rt_vk_spirv_rt_vk_soft_test[],
    rt_vk_spirv_rt_vk_interface_test[];
extern const size_t rt_vk_spirv_rt_vk_main_size, rt_vk_spirv_rt_vk_soft_test_size,
    rt_vk_spirv_rt_vk_interface_test_size;

/* Tiles (pixels or rays per dispatch), adapted per frame so that one
 * dispatch stays near RT_VK_TARGET_MS: OpenCL's budget (a GPU watchdog fires
 * after a few seconds; we keep far from it). */
#define RT_VK_TILE_MIN   1024u
#define RT_VK_TILE_MAX   (1u << 18)
#define RT_VK_TILE_FIRST 16384u
#define RT_VK_TARGET_MS  50.0
/* A dispatch that has not finished after this long is reported, not waited
 * for forever. */
#define RT_VK_FENCE_NS (120ull * 1000000000ull)
/* Items traced alone per dispatch, each with its slot of RT_VK_STATE_WORDS
 * words in the state buffer (8.5 MiB); their (item, slot) pairs follow the
 * flags in the items buffer, so 2 * RT_VK_SLOTS <= RT_VK_TILE_MAX. */
#define RT_VK_SLOTS 4096u

/* The buffers are RT_VK_BUF_* of the GPU interface table
 * (kernels/rt_interface.def), numbered by their bindings; the push
 * constants are its rt_vk_push, the specialization constants its
 * RT_VK_SPEC_*, the work group size RT_VK_LOCAL. */

/* Fault injection for the tests (rt_vk_test_loop_limit). */
static uint32_t vk_test_ballast, vk_test_alone_ballast;
static int vk_test_no_rerun;

void rt_vk_test_loop_limit(uint32_t ballast, int rerun) {
    vk_test_ballast = ballast;
    vk_test_no_rerun = !rerun;
}

void rt_vk_test_alone_ballast(uint32_t ballast) {
    vk_test_alone_ballast = ballast;
}

/* Items per alone dispatch (rerun_cut's batches), RT_VK_SLOTS unless a test
 * sets fewer to run several batches on a small frame. */
static uint32_t vk_slots = RT_VK_SLOTS;

void rt_vk_test_slots(uint32_t slots) {
    vk_slots = slots >= 1 && slots <= RT_VK_SLOTS ? slots : RT_VK_SLOTS;
}

/* What the last frame or trace re-ran (rerun_cut), for rt_vk_test_reruns. */
typedef struct vk_reruns {
    uint32_t items;      /* items traced again alone */
    uint32_t resumes;    /* item-dispatches that went on from a saved state */
    uint32_t dispatches; /* re-run and resume dispatches */
    double ms;           /* their device time */
} vk_reruns;
static vk_reruns vk_last_reruns;

void rt_vk_test_reruns(uint32_t *items, uint32_t *resumes, uint32_t *dispatches) {
    *items = vk_last_reruns.items;
    *resumes = vk_last_reruns.resumes;
    *dispatches = vk_last_reruns.dispatches;
}

/* P_ALONE is rt_vk_main again, specialised with SC_RESUME = 1: the items
 * rerun_cut traces alone, which may suspend and resume. Only that pipeline
 * carries the iteration count and the state's save and load code (about
 * half of rt_vk_main's compile time on lavapipe), and it is made only when
 * a frame or trace first has an item to re-run. */
enum { P_MAIN, P_SOFT, P_PROBE, P_ALONE, P_COUNT };
static const char *const pipeline_names[P_COUNT] = {"rt_vk_main", "rt_vk_soft_test",
                                                    "rt_vk_interface_test", "rt_vk_main"};

typedef struct vk_buf {
    VkBuffer buf;
    VkDeviceMemory mem;
    void *map;
    size_t cap;
} vk_buf;

typedef struct vk_state {
    char selector[128];
    int flush;          /* the denormal policy: 1 flush (rt_backend_config.flush_denormals) */
    uint32_t kd_shared; /* RT_VK_SPEC_KD_SHARED: RT_VK_SPEC_DEFAULT_KD_SHARED, lower in a test */
    rt_vk_device_info dev;
    VkInstance inst;
    VkPhysicalDevice phys;
    VkDevice device;
    VkQueue queue;
    VkCommandPool cpool;
    VkCommandBuffer cmd;
    VkFence fence;
    VkQueryPool qpool; /* two timestamps around each dispatch */
    VkDescriptorSetLayout dsl;
    VkPipelineLayout layout;
    VkDescriptorPool dpool;
    VkDescriptorSet set;
    int set_dirty; /* a buffer was remade: the descriptor set must be rewritten */
    VkShaderModule module[P_COUNT];
    VkPipeline pipe[P_COUNT];
    uint32_t spec[P_COUNT][RT_VK_SPEC_COUNT]; /* what each pipeline was specialised to */
    char spec_text[192];
    vk_buf buf[RT_VK_BUF_COUNT];
    rt_upload_memo memo; /* what the device holds of the layout */
    uint32_t tile;
    int lost; /* the device was lost: every later call fails with the reason */
    /* The pipeline cache kept on disk (vk_pipeline_cache.h). */
    rt_vk_pcache pcache;
} vk_state;

const uint32_t *rt_vk_module(const char *name, size_t *bytes) {
    if (!strcmp(name, "rt_vk_main")) {
        *bytes = rt_vk_spirv_rt_vk_main_size;
        return rt_vk_spirv_rt_vk_main;
    }
    if (!strcmp(name, "rt_vk_soft_test")) {
        *bytes = rt_vk_spirv_rt_vk_soft_test_size;
        return rt_vk_spirv_rt_vk_soft_test;
    }
    if (!strcmp(name, "rt_vk_interface_test")) {
        *bytes = rt_vk_spirv_rt_vk_interface_test_size;
        return rt_vk_spirv_rt_vk_interface_test;
    }
    *bytes = 0;
    return NULL;
}

/* ---- float controls ------------------------------------------------------ */

enum {
    SPV_OP_EXTENSION = 10,
    SPV_OP_ENTRY_POINT = 15,
    SPV_OP_EXECUTION_MODE = 16,
    SPV_OP_CAPABILITY = 17,
    /* execution modes and the capabilities that allow them */
    SPV_DENORM_PRESERVE = 4459,
    SPV_DENORM_FLUSH = 4460,
    SPV_SIGNED_ZERO_INF_NAN = 4461,
    SPV_RTE = 4462,
    SPV_CAP_DENORM_PRESERVE = 4464,
    SPV_CAP_DENORM_FLUSH = 4465,
    SPV_CAP_SIGNED_ZERO_INF_NAN = 4466,
    SPV_CAP_RTE = 4467
};

uint32_t *rt_vk_with_float_controls(const uint32_t *w, size_t bytes, int rte,
                                    int signed_zero_inf_nan, int denorm_preserve, int denorm_flush,
                                    size_t *out_bytes) {
    size_t n = bytes / 4;
    if (n < 5 || w[0] != 0x07230203u) return NULL;
    uint32_t modes[4], caps[4];
    int k = 0;
    if (rte) modes[k] = SPV_RTE, caps[k++] = SPV_CAP_RTE;
    if (signed_zero_inf_nan)
        modes[k] = SPV_SIGNED_ZERO_INF_NAN, caps[k++] = SPV_CAP_SIGNED_ZERO_INF_NAN;
    if (denorm_preserve) modes[k] = SPV_DENORM_PRESERVE, caps[k++] = SPV_CAP_DENORM_PRESERVE;
    if (denorm_flush) modes[k] = SPV_DENORM_FLUSH, caps[k++] = SPV_CAP_DENORM_FLUSH;
    /* Where to insert: after the last capability, the last extension (else
     * the capabilities) and the last execution mode (else the entry point). */
    size_t end_cap = 0, end_ext = 0, end_mode = 0, end_entry = 0;
    uint32_t entry = 0;
    for (size_t i = 5; i < n;) {
        uint32_t op = w[i] & 0xffffu, len = w[i] >> 16;
        if (len == 0 || i + len > n) return NULL;
        if (op == SPV_OP_CAPABILITY) end_cap = i + len;
        if (op == SPV_OP_EXTENSION) end_ext = i + len;
        if (op == SPV_OP_EXECUTION_MODE) end_mode = i + len;
        if (op == SPV_OP_ENTRY_POINT) {
            end_entry = i + len;
            entry = w[i + 2];
        }
        i += len;
    }
    if (!end_cap || !end_entry) return NULL;
    if (!end_ext) end_ext = end_cap;
    if (!end_mode) end_mode = end_entry;
    static const char ext[] = "SPV_KHR_float_controls"; /* 22 chars + NUL: 6 words */
    const uint32_t ext_words = 1 + (uint32_t)(sizeof ext + 3) / 4;
    size_t extra = k ? (size_t)k * 2 + ext_words + (size_t)k * 4 : 0;
    uint32_t *out = malloc((n + extra) * 4);
    if (!out) return NULL;
    size_t o = 0;
    for (size_t i = 0; i < n;) {
        uint32_t len = i < 5 ? 5 : w[i] >> 16;
        memcpy(out + o, w + i, len * 4);
        o += len;
        i += len;
        if (!k) continue;
        if (i == end_cap)
            for (int j = 0; j < k; j++) {
                out[o++] = (2u << 16) | SPV_OP_CAPABILITY;
                out[o++] = caps[j];
            }
        if (i == end_ext) {
            out[o++] = (ext_words << 16) | SPV_OP_EXTENSION;
            memset(out + o, 0, (ext_words - 1) * 4);
            memcpy(out + o, ext, sizeof ext);
            o += ext_words - 1;
        }
        if (i == end_mode)
            for (int j = 0; j < k; j++) {
                out[o++] = (4u << 16) | SPV_OP_EXECUTION_MODE;
                out[o++] = entry;
                out[o++] = modes[j];
                out[o++] = 32; /* the float width */
            }
    }
    *out_bytes = o * 4;
    return out;
}

/* ---- errors ---------------------------------------------------------------- */

static int out_of_memory(VkResult r) {
    return r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY;
}

/* Any failure of this backend reads "vulkan: ..." for the caller. */
static rt_status named(rt_error *err, rt_status st) {
    return rt_error_prefix(err, st, "vulkan: ");
}

static rt_status vk_fail(vk_state *s, VkResult r, const char *what, rt_error *err) {
    if (r == VK_ERROR_DEVICE_LOST) {
        s->lost = 1;
        return rt_fail(err, RT_ERROR_BACKEND, "device lost on '%s' (%s); the backend cannot go on",
                       s->dev.name, what);
    }
    return rt_fail(err, out_of_memory(r) ? RT_ERROR_OUT_OF_MEMORY : RT_ERROR_BACKEND,
                   "%s on '%s': %s", what, s->dev.name, rt_vk_result_name(r));
}

/* ---- the device ------------------------------------------------------------ */

static void destroy_buffer(vk_state *s, vk_buf *b) {
    if (b->map) vkUnmapMemory(s->device, b->mem);
    if (b->buf) vkDestroyBuffer(s->device, b->buf, NULL);
    if (b->mem) vkFreeMemory(s->device, b->mem, NULL);
    memset(b, 0, sizeof *b);
}

/* Destroys what was made on the device, the device and the instance, and
 * leaves every handle null, so that ready() may open them again. */
static void close_device(vk_state *s) {
    if (s->device) {
        vkDeviceWaitIdle(s->device);
        for (int i = 0; i < RT_VK_BUF_COUNT; i++) destroy_buffer(s, &s->buf[i]);
        for (int i = 0; i < P_COUNT; i++) {
            if (s->pipe[i]) vkDestroyPipeline(s->device, s->pipe[i], NULL);
            if (s->module[i]) vkDestroyShaderModule(s->device, s->module[i], NULL);
            s->pipe[i] = VK_NULL_HANDLE;
            s->module[i] = VK_NULL_HANDLE;
        }
        if (s->dpool) vkDestroyDescriptorPool(s->device, s->dpool, NULL);
        if (s->layout) vkDestroyPipelineLayout(s->device, s->layout, NULL);
        if (s->dsl) vkDestroyDescriptorSetLayout(s->device, s->dsl, NULL);
        if (s->qpool) vkDestroyQueryPool(s->device, s->qpool, NULL);
        if (s->fence) vkDestroyFence(s->device, s->fence, NULL);
        if (s->cpool) vkDestroyCommandPool(s->device, s->cpool, NULL);
        rt_vk_pcache_close(&s->pcache, s->device);
        vkDestroyDevice(s->device, NULL);
    }
    if (s->inst) vkDestroyInstance(s->inst, NULL);
    s->inst = VK_NULL_HANDLE;
    s->device = VK_NULL_HANDLE;
    s->fence = VK_NULL_HANDLE;
    s->qpool = VK_NULL_HANDLE;
    s->cpool = VK_NULL_HANDLE;
    s->cmd = VK_NULL_HANDLE;
    s->dpool = VK_NULL_HANDLE;
    s->set = VK_NULL_HANDLE;
    s->layout = VK_NULL_HANDLE;
    s->dsl = VK_NULL_HANDLE;
}

static void vk_destroy(void *p) {
    vk_state *s = p;
    if (!s) return;
    close_device(s);
    rt_upload_memo_free(&s->memo);
    free(s);
}

static rt_status vk_create(const rt_backend_config *config, void **state, rt_error *err) {
    vk_state *s = calloc(1, sizeof *s);
    if (!s) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "vulkan: out of memory");
    if (config->device_math == RT_DEVICE_MATH_NATIVE) {
        free(s);
        return rt_fail(err, RT_ERROR_UNSUPPORTED,
                       "vulkan: no native maths profile: Vulkan does not promise correctly rounded "
                       "division and sqrt (2.5 ulp allowed), so the shaders always compute them "
                       "in software (--device-math portable or auto)");
    }
    snprintf(s->selector, sizeof s->selector, "%s", config->device ? config->device : "");
    s->flush = config->flush_denormals;
    s->kd_shared = RT_VK_SPEC_DEFAULT_KD_SHARED;
    s->tile = RT_VK_TILE_FIRST;
    *state = s;
    return RT_OK;
}

/* The instance, the selected device, its queue, command buffer, fence,
 * timestamp queries and the one descriptor set layout (14 storage buffers)
 * every pipeline shares. */
static rt_status open_device(vk_state *s, rt_error *err) {
    rt_status st = rt_vk_instance(&s->inst, err);
    if (st != RT_OK) return st;
    rt_vk_device_info *devs;
    VkPhysicalDevice *handles;
    int count;
    st = rt_vk_enumerate(s->inst, &devs, &handles, &count, err);
    if (st != RT_OK) return st;
    int pick = rt_vk_select(devs, count, s->selector, err);
    if (pick >= 0) {
        s->dev = devs[pick];
        s->phys = handles[pick];
    }
    free(devs);
    free(handles);
    if (pick < 0) return RT_ERROR_INVALID_ARGUMENT;

    float priority = 1.0f;
    VkDeviceQueueCreateInfo qi = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qi.queueFamilyIndex = s->dev.queue_family;
    qi.queueCount = 1;
    qi.pQueuePriorities = &priority;
    VkDeviceCreateInfo di = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    di.queueCreateInfoCount = 1;
    di.pQueueCreateInfos = &qi;
    VkResult r = vkCreateDevice(s->phys, &di, NULL, &s->device);
    if (r != VK_SUCCESS) return vk_fail(s, r, "creating the device", err);
    vkGetDeviceQueue(s->device, s->dev.queue_family, 0, &s->queue);

    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pi.queueFamilyIndex = s->dev.queue_family;
    r = vkCreateCommandPool(s->device, &pi, NULL, &s->cpool);
    if (r != VK_SUCCESS) return vk_fail(s, r, "creating a command pool", err);
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = s->cpool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    r = vkAllocateCommandBuffers(s->device, &ai, &s->cmd);
    if (r != VK_SUCCESS) return vk_fail(s, r, "allocating a command buffer", err);
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    r = vkCreateFence(s->device, &fi, NULL, &s->fence);
    if (r != VK_SUCCESS) return vk_fail(s, r, "creating a fence", err);
    if (s->dev.timestamps) {
        VkQueryPoolCreateInfo q = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        q.queryType = VK_QUERY_TYPE_TIMESTAMP;
        q.queryCount = 2;
        r = vkCreateQueryPool(s->device, &q, NULL, &s->qpool);
        if (r != VK_SUCCESS) return vk_fail(s, r, "creating a timestamp query pool", err);
    }

    VkDescriptorSetLayoutBinding b[RT_VK_BUF_COUNT];
    for (int i = 0; i < RT_VK_BUF_COUNT; i++) {
        memset(&b[i], 0, sizeof b[i]);
        b[i].binding = (uint32_t)i;
        b[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        b[i].descriptorCount = 1;
        b[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo li = {.sType =
                                              VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    li.bindingCount = RT_VK_BUF_COUNT;
    li.pBindings = b;
    r = vkCreateDescriptorSetLayout(s->device, &li, NULL, &s->dsl);
    if (r != VK_SUCCESS) return vk_fail(s, r, "creating the descriptor set layout", err);
    VkPushConstantRange pr = {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(rt_vk_push)};
    VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &s->dsl;
    pli.pushConstantRangeCount = 1;
    pli.pPushConstantRanges = &pr;
    r = vkCreatePipelineLayout(s->device, &pli, NULL, &s->layout);
    if (r != VK_SUCCESS) return vk_fail(s, r, "creating the pipeline layout", err);
    VkDescriptorPoolSize ps = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, RT_VK_BUF_COUNT};
    VkDescriptorPoolCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpi.maxSets = 1;
    dpi.poolSizeCount = 1;
    dpi.pPoolSizes = &ps;
    r = vkCreateDescriptorPool(s->device, &dpi, NULL, &s->dpool);
    if (r != VK_SUCCESS) return vk_fail(s, r, "creating the descriptor pool", err);
    VkDescriptorSetAllocateInfo dai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    dai.descriptorPool = s->dpool;
    dai.descriptorSetCount = 1;
    dai.pSetLayouts = &s->dsl;
    r = vkAllocateDescriptorSets(s->device, &dai, &s->set);
    if (r != VK_SUCCESS) return vk_fail(s, r, "allocating the descriptor set", err);
    s->set_dirty = 1;
    return RT_OK;
}

/* Opens the device at the first use; fails at once once it was lost. */
static rt_status ready(vk_state *s, rt_error *err) {
    if (s->lost)
        return rt_fail(err, RT_ERROR_BACKEND, "device '%s' was lost earlier; make a new renderer",
                       s->dev.name);
    if (s->device) return RT_OK;
    rt_status st = open_device(s, err);
    if (st != RT_OK) close_device(s); /* start afresh next time */
    return st;
}

/* ---- pipelines ----------------------------------------------------------------- */

static rt_status bind_all(vk_state *s, rt_error *err);
static rt_status dispatch(vk_state *s, int p, const rt_vk_push *push, double *ms, rt_error *err);

/* Pipeline p specialised to spec (made again only when spec changed). The
 * module gets the device's float controls first. */
static rt_status pipeline(vk_state *s, int p, const uint32_t spec[RT_VK_SPEC_COUNT], double *ms,
                          rt_error *err) {
    if (s->pipe[p] && memcmp(s->spec[p], spec, sizeof s->spec[p]) == 0) return RT_OK;
    double t0 = rt_now_ms();
    VkResult r;
    if (!s->module[p]) {
        size_t bytes, patched_bytes = 0;
        const uint32_t *words = rt_vk_module(pipeline_names[p], &bytes);
        uint32_t *patched = NULL;
        if (s->dev.float_controls) {
            patched =
                rt_vk_with_float_controls(words, bytes, s->dev.rte, s->dev.signed_zero_inf_nan,
                                          !s->flush && s->dev.denorm_preserve,
                                          s->flush && s->dev.denorm_flush, &patched_bytes);
            if (!patched) return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
        }
        VkShaderModuleCreateInfo mi = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        mi.codeSize = patched ? patched_bytes : bytes;
        mi.pCode = patched ? patched : words;
        r = vkCreateShaderModule(s->device, &mi, NULL, &s->module[p]);
        free(patched);
        if (r != VK_SUCCESS) return vk_fail(s, r, "creating a shader module", err);
    }
    if (s->pipe[p]) vkDestroyPipeline(s->device, s->pipe[p], NULL);
    s->pipe[p] = VK_NULL_HANDLE;
    VkSpecializationMapEntry map[RT_VK_SPEC_COUNT];
    for (uint32_t i = 0; i < RT_VK_SPEC_COUNT; i++) {
        map[i].constantID = i;
        map[i].offset = i * 4;
        map[i].size = 4;
    }
    VkSpecializationInfo si = {RT_VK_SPEC_COUNT, map, RT_VK_SPEC_COUNT * 4, spec};
    VkComputePipelineCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = s->module[p];
    ci.stage.pName = "main";
    ci.stage.pSpecializationInfo = &si;
    ci.layout = s->layout;
    VkPipelineCache cache = rt_vk_pcache_get(&s->pcache, s->device, s->phys);
    r = vkCreateComputePipelines(s->device, cache, 1, &ci, NULL, &s->pipe[p]);
    if (r != VK_SUCCESS) {
        s->pipe[p] = VK_NULL_HANDLE;
        return vk_fail(s, r, "creating the compute pipeline", err);
    }
    memcpy(s->spec[p], spec, sizeof s->spec[p]);
    /* One empty dispatch (count 0: every invocation returns at once): some
     * drivers (lavapipe) compile the shader at its first dispatch, which
     * would otherwise land in the first frame's time. */
    rt_vk_push none;
    memset(&none, 0, sizeof none);
    double ignored;
    rt_status st = bind_all(s, err);
    if (st == RT_OK) st = dispatch(s, p, &none, &ignored, err);
    if (st == RT_OK) rt_vk_pcache_save(&s->pcache, s->device); /* when it changed */
    *ms += rt_now_ms() - t0;
    return st;
}

/* The specialization constants for the scene: its header flags and triangle
 * test, as OpenCL's -D switches (scene_defines in cl_backend.c). */
static void scene_spec(const rt_flat *f, int flush, uint32_t kd_shared,
                       uint32_t spec[RT_VK_SPEC_COUNT]) {
    uint32_t flags = f->hdr.flags;
    spec[RT_VK_SPEC_FLAGS] = flags;
    spec[RT_VK_SPEC_INST_SET] = (flags & RT_SCENE_SINGLE) ? RT_INST_IDENTITY : 0u;
    spec[RT_VK_SPEC_INST_MASK] = RT_INST_IDENTITY |
                                 ((flags & RT_SCENE_NORMALS) ? RT_INST_NORMALS : 0u) |
                                 (f->kd_node_count ? RT_INST_KD : 0u); /* the kd traversal */
    spec[RT_VK_SPEC_TRI_METHOD] = f->hdr.tri_method;
    /* The soft maths' denormal mode, the policy's. */
    spec[RT_VK_SPEC_DENORM_FLUSH] = flush ? 1u : 0u;
    spec[RT_VK_SPEC_KD_SHARED] = kd_shared;
    spec[RT_VK_SPEC_RESUME] = 0u; /* rerun_cut makes the alone pipeline with 1 */
}

/* ---- buffers ----------------------------------------------------------------- */

/* A memory type host-visible and coherent (device-local too when there is
 * one) among the allowed bits; -1 when none. */
static int memory_type(vk_state *s, uint32_t allowed) {
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(s->phys, &mp);
    const VkMemoryPropertyFlags need =
        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    int best = -1;
    for (uint32_t i = 0; i < mp.memoryTypeCount; i++) {
        if (!(allowed & (1u << i)) || (mp.memoryTypes[i].propertyFlags & need) != need) continue;
        if (best < 0) best = (int)i;
        if (mp.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) return (int)i;
    }
    return best;
}

/* Makes buffer b hold at least bytes (never 0: empty arrays get a stub). Its
 * contents are gone when it was remade (*remade = 1). */
static rt_status ensure(vk_state *s, int b, size_t bytes, int *remade, rt_error *err) {
    if (bytes < 16) bytes = 16;
    bytes = (bytes + 15) & ~(size_t)15;
    *remade = 0;
    vk_buf *vb = &s->buf[b];
    if (vb->buf && vb->cap >= bytes) return RT_OK;
    destroy_buffer(s, vb);
    s->set_dirty = 1;
    *remade = 1;
    if ((uint64_t)bytes > s->dev.max_buffer)
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY,
                       "out of device memory: buffer '%s' needs %zu bytes, more than the largest "
                       "storage buffer of '%s' (%llu bytes)",
                       rt_vk_buffer_what(b), bytes, s->dev.name,
                       (unsigned long long)s->dev.max_buffer);
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = bytes;
    bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkResult r = vkCreateBuffer(s->device, &bi, NULL, &vb->buf);
    VkMemoryRequirements req;
    int type = -1;
    if (r == VK_SUCCESS) {
        vkGetBufferMemoryRequirements(s->device, vb->buf, &req);
        type = memory_type(s, req.memoryTypeBits);
        if (type < 0) r = VK_ERROR_FEATURE_NOT_PRESENT;
    }
    if (r == VK_SUCCESS) {
        VkMemoryAllocateInfo mi = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        mi.allocationSize = req.size;
        mi.memoryTypeIndex = (uint32_t)type;
        r = vkAllocateMemory(s->device, &mi, NULL, &vb->mem);
    }
    if (r == VK_SUCCESS) r = vkBindBufferMemory(s->device, vb->buf, vb->mem, 0);
    if (r == VK_SUCCESS) r = vkMapMemory(s->device, vb->mem, 0, VK_WHOLE_SIZE, 0, &vb->map);
    if (r != VK_SUCCESS) {
        destroy_buffer(s, vb);
        if (r == VK_ERROR_DEVICE_LOST) return vk_fail(s, r, "allocating a buffer", err);
        return rt_fail(err, out_of_memory(r) ? RT_ERROR_OUT_OF_MEMORY : RT_ERROR_BACKEND,
                       "%s: buffer '%s' of %zu bytes on '%s' (%s)",
                       out_of_memory(r) ? "out of device memory" : "cannot allocate",
                       rt_vk_buffer_what(b), bytes, s->dev.name,
                       type < 0 ? "no host-visible coherent memory" : rt_vk_result_name(r));
    }
    vb->cap = bytes;
    return RT_OK;
}

/* Every binding has a buffer (stubs for the unused ones), and the set names
 * the current ones. */
static rt_status bind_all(vk_state *s, rt_error *err) {
    for (int b = 0; b < RT_VK_BUF_COUNT; b++) {
        int remade;
        rt_status st = ensure(s, b, 16, &remade, err);
        if (st != RT_OK) return st;
    }
    if (!s->set_dirty) return RT_OK;
    VkDescriptorBufferInfo info[RT_VK_BUF_COUNT];
    VkWriteDescriptorSet w[RT_VK_BUF_COUNT];
    for (int b = 0; b < RT_VK_BUF_COUNT; b++) {
        info[b].buffer = s->buf[b].buf;
        info[b].offset = 0;
        info[b].range = VK_WHOLE_SIZE;
        memset(&w[b], 0, sizeof w[b]);
        w[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        w[b].dstSet = s->set;
        w[b].dstBinding = (uint32_t)b;
        w[b].descriptorCount = 1;
        w[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        w[b].pBufferInfo = &info[b];
    }
    vkUpdateDescriptorSets(s->device, RT_VK_BUF_COUNT, w, 0, NULL);
    s->set_dirty = 0;
    return RT_OK;
}

/* The buffer of each array of an upload plan (upload_plan.h). */
static const int upload_buffer[RT_UP_COUNT] = {
    RT_VK_BUF_HDR,         RT_VK_BUF_NODES,    RT_VK_BUF_TRIS,      RT_VK_BUF_TRI_IDS,
    RT_VK_BUF_TRI_NORMALS, RT_VK_BUF_TRI_MATS, RT_VK_BUF_INSTANCES, RT_VK_BUF_INST_IDS,
    RT_VK_BUF_MATERIALS,   RT_VK_BUF_LIGHTS,   RT_VK_BUF_KD_NODES};

typedef struct vk_upload {
    vk_state *s;
    uint64_t *bytes;
} vk_upload;

static rt_status vk_emit(void *user, const rt_upload_copy *c) {
    vk_upload *u = user;
    memcpy((char *)u->s->buf[upload_buffer[c->array]].map + c->offset, c->src, c->bytes);
    *u->bytes += c->bytes;
    return RT_OK;
}

/* Brings the device's copy of the layout up to date (upload_plan.h: only
 * what changed), copying into the mapped buffers; *bytes counts the copies. */
static rt_status upload_scene(vk_state *s, const rt_backend_layout *layout, uint64_t *bytes,
                              double *ms, rt_error *err) {
    double t0 = rt_now_ms();
    size_t cap[RT_UP_COUNT];
    for (int i = 0; i < RT_UP_COUNT; i++)
        cap[i] = s->buf[upload_buffer[i]].buf ? s->buf[upload_buffer[i]].cap : 0;
    rt_upload_plan plan;
    if (rt_upload_plan_make(&s->memo, layout, cap, &plan) != RT_OK)
        return rt_fail(err, RT_ERROR_OUT_OF_MEMORY, "out of memory");
    int remade[RT_UP_COUNT] = {0};
    rt_status st = RT_OK;
    for (int i = 0; plan.buffers && i < RT_UP_COUNT && st == RT_OK; i++)
        st = ensure(s, upload_buffer[i], plan.bytes[i], &remade[i], err);
    vk_upload u = {s, bytes};
    if (st == RT_OK) st = rt_upload_plan_run(&plan, layout, remade, vk_emit, &u);
    rt_upload_plan_finish(&plan, &s->memo, layout, st == RT_OK);
    *ms += rt_now_ms() - t0;
    return st;
}

/* ---- dispatches ---------------------------------------------------------------- */

/* Runs pipeline p over groups work groups (at least one) with the push
 * constants push and waits. *ms gets the device's time between two
 * timestamps around the dispatch (the host's wall time where the queue has
 * no timestamps). */
static rt_status dispatch_groups(vk_state *s, int p, const rt_vk_push *push, uint32_t groups,
                                 double *ms, rt_error *err) {
    double t0 = rt_now_ms();
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VkResult r = vkResetCommandBuffer(s->cmd, 0);
    if (r == VK_SUCCESS) r = vkBeginCommandBuffer(s->cmd, &bi);
    if (r != VK_SUCCESS) return vk_fail(s, r, "recording a dispatch", err);
    if (s->qpool) vkCmdResetQueryPool(s->cmd, s->qpool, 0, 2);
    vkCmdBindPipeline(s->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s->pipe[p]);
    vkCmdBindDescriptorSets(s->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s->layout, 0, 1, &s->set, 0,
                            NULL);
    vkCmdPushConstants(s->cmd, s->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof *push, push);
    if (s->qpool) vkCmdWriteTimestamp(s->cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, s->qpool, 0);
    vkCmdDispatch(s->cmd, groups ? groups : 1, 1, 1);
    if (s->qpool) vkCmdWriteTimestamp(s->cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, s->qpool, 1);
    /* The shader's writes are made visible to the host's reads. */
    VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(s->cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                         0, 1, &mb, 0, NULL, 0, NULL);
    r = vkEndCommandBuffer(s->cmd);
    if (r != VK_SUCCESS) return vk_fail(s, r, "recording a dispatch", err);
    VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &s->cmd;
    r = vkQueueSubmit(s->queue, 1, &si, s->fence);
    if (r == VK_SUCCESS) r = vkWaitForFences(s->device, 1, &s->fence, VK_TRUE, RT_VK_FENCE_NS);
    if (r == VK_TIMEOUT) {
        s->lost = 1; /* the fence may still signal: nothing can be reused */
        return rt_fail(err, RT_ERROR_BACKEND, "%s on '%s' did not finish within %llu s",
                       pipeline_names[p], s->dev.name, RT_VK_FENCE_NS / 1000000000ull);
    }
    if (r != VK_SUCCESS) return vk_fail(s, r, pipeline_names[p], err);
    vkResetFences(s->device, 1, &s->fence);
    uint64_t ts[2];
    if (s->qpool &&
        vkGetQueryPoolResults(s->device, s->qpool, 0, 2, sizeof ts, ts, sizeof ts[0],
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) == VK_SUCCESS &&
        ts[1] >= ts[0])
        *ms = (double)(ts[1] - ts[0]) * (double)s->dev.timestamp_period * 1e-6;
    else
        *ms = rt_now_ms() - t0;
    return RT_OK;
}

/* Runs pipeline p over push->count items (push->stride invocations each in
 * a re-run), rounded up to whole work groups (the shaders skip those past
 * the count), and waits; *ms as dispatch_groups. */
static rt_status dispatch(vk_state *s, int p, const rt_vk_push *push, double *ms, rt_error *err) {
    uint64_t invocations = (uint64_t)push->count * (push->stride > 1 ? push->stride : 1);
    return dispatch_groups(s, p, push, (uint32_t)((invocations + RT_VK_LOCAL - 1) / RT_VK_LOCAL),
                           ms, err);
}

/* The next tile from the last full tile's time: halve above the target,
 * double below a quarter of it (kept in the state for the next frame). */
static uint32_t next_tile(uint32_t tile, double ms) {
    if (ms > RT_VK_TARGET_MS && tile / 2 >= RT_VK_TILE_MIN) return tile / 2;
    if (ms < RT_VK_TARGET_MS / 4 && tile < RT_VK_TILE_MAX) return tile * 2;
    return tile;
}

/* The error for item i of the tile of push (width > 0: pixels of a frame
 * that wide, else rays numbered from base) cut even alone. */
static rt_status cut_error(vk_state *s, const rt_vk_push *push, size_t base, int width, uint32_t i,
                           int alone, rt_error *err) {
    char why[400];
    snprintf(why, sizeof why,
             "needs more loop iterations than the driver runs in one shader invocation (llvmpipe "
             "and lavapipe stop every loop after 65535 in all)%s, so its result would be wrong",
             alone ? " although it ran alone and saves its state before half of them" : "");
    if (width > 0) {
        size_t p = (size_t)push->first + i;
        return rt_fail(err, RT_ERROR_BACKEND, "vulkan on '%s': pixel (%zu, %zu) %s", s->dev.name,
                       p % (size_t)width, p / (size_t)width, why);
    }
    return rt_fail(err, RT_ERROR_BACKEND, "vulkan on '%s': ray %zu %s", s->dev.name, base + i, why);
}

/* The items of the last dispatch (push: its first pass) that the driver's
 * loop limit may have cut short (items[i] = 1: rt_vk_main.comp's canary)
 * are traced again, each alone in its work group, so that the limit is one
 * item's to spend; in batches of RT_VK_SLOTS, the (item, slot) pairs from
 * items[push->list_at] on. An item alone suspends before the limit
 * (items[i] = 2, its state in its slot: rt_vk_resume.glsl) and the next
 * dispatch of the batch resumes it, until none is left: a ray that needs
 * many loop iterations costs dispatches, not an error. An item cut even
 * alone (the canary, the safety net of the shader's own count) is an error
 * that names it, never a wrong result; so is every cut item when the tests
 * forbid re-runs. width > 0: the items are pixels of a frame that wide, else
 * rays numbered from base. */
static rt_status rerun_cut(vk_state *s, const rt_vk_push *push, size_t base, int width,
                           vk_reruns *rr, double *compile_ms, rt_error *err) {
    uint32_t *items = s->buf[RT_VK_BUF_ITEMS].map;
    uint32_t *pairs = items + push->list_at;
    int any = 0;
    for (uint32_t i = 0; i < push->count; i++) {
        if (items[i] && vk_test_no_rerun) return cut_error(s, push, base, width, i, 0, err);
        any |= items[i] != 0;
    }
    if (!any) return RT_OK;
    /* The alone pipeline: P_MAIN's specialisation with SC_RESUME = 1. */
    uint32_t spec[RT_VK_SPEC_COUNT];
    memcpy(spec, s->spec[P_MAIN], sizeof spec);
    spec[RT_VK_SPEC_RESUME] = 1u;
    rt_status made = pipeline(s, P_ALONE, spec, compile_ms, err);
    if (made != RT_OK) return made;
    for (uint32_t next = 0; next < push->count;) {
        /* The next batch: up to RT_VK_SLOTS cut items, slot k each. */
        uint32_t m = 0;
        for (; next < push->count && m < vk_slots; next++)
            if (items[next]) {
                pairs[2 * m] = next;
                pairs[2 * m + 1] = m;
                m++;
            }
        rt_vk_push again = *push;
        again.stride = RT_VK_LOCAL;
        again.ballast = vk_test_alone_ballast;
        again.resume = 0;
        if (m) rr->items += m;
        while (m) {
            again.count = m;
            double ms;
            rt_status st = dispatch(s, P_ALONE, &again, &ms, err);
            if (st != RT_OK) return st;
            rr->dispatches++;
            rr->ms += ms;
            /* Keep the suspended items (in place: k <= q) for the next. */
            uint32_t k = 0;
            for (uint32_t q = 0; q < m; q++) {
                uint32_t i = pairs[2 * q];
                if (items[i] == 1) return cut_error(s, push, base, width, i, 1, err);
                if (items[i] != 2) continue;
                pairs[2 * k] = i;
                pairs[2 * k + 1] = pairs[2 * q + 1];
                k++;
            }
            m = k;
            rr->resumes += m;
            again.resume = 1;
        }
    }
    return RT_OK;
}

/* ---- the backend --------------------------------------------------------------- */

static rt_status vk_prepare(void *state, const rt_backend_layout *layout, rt_render_stats *stats,
                            rt_error *err) {
    vk_state *s = state;
    rt_status st = ready(s, err);
    uint32_t spec[RT_VK_SPEC_COUNT];
    scene_spec(layout->flat, s->flush, s->kd_shared, spec);
    if (st == RT_OK) st = pipeline(s, P_MAIN, spec, &stats->compile_ms, err);
    if (st == RT_OK) st = upload_scene(s, layout, &stats->upload_bytes, &stats->upload_ms, err);
    if (st != RT_OK) return named(err, st);
    snprintf(s->spec_text, sizeof s->spec_text,
             "specialization constants: flags=%u inst_set=%u inst_mask=%u tri_method=%u "
             "denormal_flush=%u kd=%s",
             spec[RT_VK_SPEC_FLAGS], spec[RT_VK_SPEC_INST_SET], spec[RT_VK_SPEC_INST_MASK],
             spec[RT_VK_SPEC_TRI_METHOD], spec[RT_VK_SPEC_DENORM_FLUSH],
             (spec[RT_VK_SPEC_INST_MASK] & RT_INST_KD) ? "yes" : "no");
    snprintf(stats->device, sizeof stats->device, "%.127s", s->dev.name);
    snprintf(stats->specialisation, sizeof stats->specialisation, "%s", s->spec_text);
    stats->device_options[0] = 0;
    stats->exact = s->flush ? s->dev.exact_flush : s->dev.exact;
    stats->math_profile = "portable";
    stats->denormals = s->flush ? "flush" : "preserve";
    return RT_OK;
}

/* rt_render_stats.threads: what ran the frame's invocations at once. On a
 * CPU device, its threads: for Mesa's lavapipe (llvmpipe) LP_NUM_THREADS
 * where set, else one per online CPU (none of its own on one CPU: the
 * calling thread), at most llvmpipe's LP_MAX_THREADS (32); another CPU
 * device one per online CPU. On a GPU, the invocations of the frame's
 * largest dispatch (its largest tile, one invocation per pixel). */
static int vk_threads(const vk_state *s, uint32_t tile_pixels) {
    if (strcmp(s->dev.type, "CPU") != 0) return (int)tile_pixels;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    if (cpus < 1) cpus = 1;
    if (!strstr(s->dev.name, "llvmpipe")) return (int)cpus;
    const char *env = getenv("LP_NUM_THREADS");
    long n = env && *env ? strtol(env, NULL, 10) : (cpus > 1 ? cpus : 0);
    if (n > 32) n = 32;
    return n < 1 ? 1 : (int)n;
}

/* The buffers of every dispatch of the main pipeline besides its input and
 * output, for a tile of RT_VK_TILE_MAX items: the counters, the items to
 * re-run (rerun_cut) and the suspended items' state slots; in that order. */
static rt_status ensure_main_buffers(vk_state *s, int *remade, rt_error *err) {
    rt_status st = ensure(s, RT_VK_BUF_COUNTERS, sizeof(rt_counters) * RT_VK_TILE_MAX, remade, err);
    if (st == RT_OK)
        st = ensure(s, RT_VK_BUF_ITEMS, 2 * sizeof(uint32_t) * RT_VK_TILE_MAX, remade, err);
    if (st == RT_OK)
        st = ensure(s, RT_VK_BUF_STATE, sizeof(uint32_t) * RT_VK_STATE_WORDS * RT_VK_SLOTS, remade,
                    err);
    return st;
}

static rt_status vk_render(void *state, const rt_backend_layout *layout,
                           const rt_backend_frame *frame, rt_render_stats *stats, rt_error *err) {
    vk_state *s = state;
    const rt_scene_header *h = &layout->flat->hdr;
    uint32_t pixels = (uint32_t)h->width * (uint32_t)h->height;
    /* The framebuffer buffer holds one tile (the shader writes tile-relative
     * pixels), copied into the frame after each dispatch: no frame is too
     * large for the device's largest storage buffer. */
    size_t px_bytes = sizeof(float) * (size_t)frame->channels;
    int remade;
    rt_status st = ensure(s, RT_VK_BUF_FB, px_bytes * RT_VK_TILE_MAX, &remade, err);
    if (st == RT_OK) st = ensure_main_buffers(s, &remade, err);
    if (st == RT_OK) st = bind_all(s, err);
    if (st != RT_OK) return named(err, st);
    vk_reruns rr;
    memset(&rr, 0, sizeof rr);
    double t_render = rt_now_ms();
    const rt_counters *counts = s->buf[RT_VK_BUF_COUNTERS].map;
    for (uint32_t first = 0; first < pixels && st == RT_OK;) {
        uint32_t per = s->tile;
        uint32_t n = pixels - first < per ? pixels - first : per;
        rt_vk_push push = {first,        n, (int32_t)frame->aov, frame->channels, 0, 0,
                           RT_VK_CANARY, 1, vk_test_ballast,     RT_VK_TILE_MAX,  0, 0};
        double ms = 0.0;
        st = dispatch(s, P_MAIN, &push, &ms, err);
        uint32_t before = rr.dispatches;
        double before_ms = rr.ms;
        if (st == RT_OK) st = rerun_cut(s, &push, 0, h->width, &rr, &stats->compile_ms, err);
        if (st != RT_OK) break;
        stats->launches += rr.dispatches - before;
        stats->kernel_ms[1] += ms + (rr.ms - before_ms);
        stats->launches++;
        if (n > stats->tile_pixels) stats->tile_pixels = n;
        double t0 = rt_now_ms();
        memcpy(frame->pixels + (size_t)first * (size_t)frame->channels, s->buf[RT_VK_BUF_FB].map,
               px_bytes * n);
        stats->download_ms += rt_now_ms() - t0;
        if (frame->want_counts)
            for (uint32_t i = 0; i < n; i++) {
                stats->rays += counts[i].rays;
                stats->box_tests += counts[i].box_tests;
                stats->tri_tests += counts[i].tri_tests;
            }
        first += n;
        if (n == per) s->tile = next_tile(s->tile, ms);
        if (frame->progress) frame->progress(frame->progress_user, (double)first / pixels);
    }
    vk_last_reruns = rr;
    if (st != RT_OK) return named(err, st);
    if (rr.items)
        snprintf(stats->kernels, sizeof stats->kernels, "vulkan: %u px re-run alone, %u resumed",
                 rr.items, rr.resumes);
    else
        snprintf(stats->kernels, sizeof stats->kernels, "vulkan rt_vk_main, portable maths");
    stats->render_ms = rt_now_ms() - t_render;
    stats->primary_rays = pixels;
    stats->threads = vk_threads(s, stats->tile_pixels);
    return RT_OK;
}

static rt_status vk_trace(void *state, const rt_backend_layout *layout, const rt_ray *rays,
                          const uint32_t *masks, size_t count, rt_hit_d *hits, int any_hit,
                          rt_trace_path path, rt_trace_stats *stats, rt_error *err) {
    vk_state *s = state;
    (void)path;   /* the packet backend's choice; one path here */
    (void)stats;  /* the renderer times the call */
    (void)layout; /* vk_prepare uploaded it */
    int remade;
    rt_status st = ensure(s, RT_VK_BUF_RAYS, sizeof(rt_ray) * RT_VK_TILE_MAX, &remade, err);
    if (st == RT_OK)
        st = ensure(s, RT_VK_BUF_HITS, sizeof(rt_hit_d) * RT_VK_TILE_MAX, &remade, err);
    if (st == RT_OK) st = ensure_main_buffers(s, &remade, err);
    if (st == RT_OK && masks)
        st = ensure(s, RT_VK_BUF_MASKS, sizeof(uint32_t) * RT_VK_TILE_MAX, &remade, err);
    if (st == RT_OK) st = bind_all(s, err);
    vk_reruns rr;
    memset(&rr, 0, sizeof rr);
    for (size_t first = 0; first < count && st == RT_OK;) {
        uint32_t n = (uint32_t)(count - first < s->tile ? count - first : s->tile);
        memcpy(s->buf[RT_VK_BUF_RAYS].map, rays + first, sizeof(rt_ray) * n);
        if (masks) memcpy(s->buf[RT_VK_BUF_MASKS].map, masks + first, sizeof(uint32_t) * n);
        rt_vk_push push = {0,
                           n,
                           0,
                           0,
                           any_hit ? 1 : 0,
                           1,
                           RT_VK_CANARY,
                           1,
                           vk_test_ballast,
                           RT_VK_TILE_MAX,
                           0,
                           masks != NULL};
        double ms = 0.0;
        st = dispatch(s, P_MAIN, &push, &ms, err);
        double compile_ms = 0.0; /* the alone pipeline's, when it is made here */
        if (st == RT_OK) st = rerun_cut(s, &push, first, 0, &rr, &compile_ms, err);
        if (st != RT_OK) break;
        memcpy(hits + first, s->buf[RT_VK_BUF_HITS].map, sizeof(rt_hit_d) * n);
        first += n;
        if (n == s->tile) s->tile = next_tile(s->tile, ms);
    }
    vk_last_reruns = rr;
    return named(err, st);
}

static int vk_available(rt_error *why) {
    rt_vk_device_info *devs;
    int count;
    if (rt_vk_devices(&devs, &count, why) != RT_OK) return 0;
    free(devs);
    return 1;
}

/* A backend state on device (NULL: the default), for the test hooks below. */
static rt_status create_on(const char *device, vk_state **out, rt_error *err) {
    rt_backend_config config;
    memset(&config, 0, sizeof config);
    config.device = device;
    void *state = NULL;
    rt_status st = vk_create(&config, &state, err);
    *out = state;
    return st;
}

rt_status rt_vk_soft_math_run(const char *device, const uint32_t *operands, size_t count, int ftz,
                              uint32_t *results, rt_error *err) {
    vk_state *s;
    rt_status st = create_on(device, &s, err);
    if (st != RT_OK) return st;
    uint32_t spec[RT_VK_SPEC_COUNT];
    rt_vk_spec_defaults(spec);
    spec[RT_VK_SPEC_DENORM_FLUSH] = ftz ? 1u : 0u;
    double ms = 0.0;
    int remade;
    st = ready(s, err);
    if (st == RT_OK) st = pipeline(s, P_SOFT, spec, &ms, err);
    const size_t tile = 1u << 16;
    if (st == RT_OK) st = ensure(s, RT_VK_BUF_RAYS, 16 * tile, &remade, err);
    if (st == RT_OK) st = ensure(s, RT_VK_BUF_HITS, 12 * tile, &remade, err);
    if (st == RT_OK) st = bind_all(s, err);
    for (size_t first = 0; first < count && st == RT_OK;) {
        uint32_t n = (uint32_t)(count - first < tile ? count - first : tile);
        memcpy(s->buf[RT_VK_BUF_RAYS].map, operands + 4 * first, 16 * (size_t)n);
        rt_vk_push push = {0, n, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0};
        st = dispatch(s, P_SOFT, &push, &ms, err);
        if (st == RT_OK) memcpy(results + 3 * first, s->buf[RT_VK_BUF_HITS].map, 12 * (size_t)n);
        first += n;
    }
    vk_destroy(s);
    return named(err, st);
}

rt_status rt_vk_interface_probe(const char *device, const void *const in[RT_VK_BUF_COUNT],
                                void *const out[RT_VK_BUF_COUNT],
                                const size_t bytes[RT_VK_BUF_COUNT], const rt_vk_push *push,
                                rt_error *err) {
    vk_state *s;
    rt_status st = create_on(device, &s, err);
    if (st != RT_OK) return st;
    uint32_t spec[RT_VK_SPEC_COUNT];
    rt_vk_spec_defaults(spec);
    double ms = 0.0;
    int remade;
    st = ready(s, err);
    if (st == RT_OK) st = pipeline(s, P_PROBE, spec, &ms, err);
    for (int b = 0; b < RT_VK_BUF_COUNT && st == RT_OK; b++)
        if (bytes[b]) st = ensure(s, b, bytes[b], &remade, err);
    if (st == RT_OK) st = bind_all(s, err);
    for (int b = 0; b < RT_VK_BUF_COUNT && st == RT_OK; b++)
        if (bytes[b] && in[b]) memcpy(s->buf[b].map, in[b], bytes[b]);
    if (st == RT_OK) st = dispatch_groups(s, P_PROBE, push, 1, &ms, err);
    for (int b = 0; b < RT_VK_BUF_COUNT && st == RT_OK; b++)
        if (bytes[b] && out[b]) memcpy(out[b], s->buf[b].map, bytes[b]);
    vk_destroy(s);
    return named(err, st);
}

rt_status rt_vk_trace_kd_stack(const char *device, const rt_flat *flat, const rt_ray *rays,
                               size_t count, int any_hit, uint32_t kd_shared_cells, rt_hit_d *hits,
                               rt_error *err) {
    if (kd_shared_cells > RT_VK_SPEC_DEFAULT_KD_SHARED)
        return rt_fail(err, RT_ERROR_INVALID_ARGUMENT, "vulkan: at most %u shared kd stack cells",
                       (unsigned)RT_VK_SPEC_DEFAULT_KD_SHARED);
    vk_state *s;
    rt_status st = create_on(device, &s, err);
    if (st != RT_OK) return st;
    s->kd_shared = kd_shared_cells;
    rt_backend_layout layout;
    memset(&layout, 0, sizeof layout);
    layout.flat = flat;
    layout.layout_generation = 1;
    layout.mesh_generation = 1;
    rt_render_stats stats;
    memset(&stats, 0, sizeof stats);
    st = vk_prepare(s, &layout, &stats, err);
    if (st == RT_OK)
        st = vk_trace(s, &layout, rays, NULL, count, hits, any_hit, RT_TRACE_PATH_AUTO, NULL, err);
    vk_destroy(s);
    return st;
}

const rt_backend_ops rt_backend_vulkan = {"vulkan", vk_available, vk_create, vk_prepare, vk_render,
                                          vk_trace, vk_destroy,   NULL,      NULL};
