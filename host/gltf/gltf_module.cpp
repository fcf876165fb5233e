/* SPDX-License-Identifier: Apache-2.0 */
// gltf_module.cpp - the glTF module (librtcl_gltf.so, formats/gltf_module.h):
// .gltf and .glb files through tinygltf, handed back as plain C arrays.
//
// A module of its own, loaded by the library on the first glTF file
// (formats/gltf_module_load.c), so that programs that read none never map
// tinygltf or the C++ runtime. Every entry point catches every exception.
// Every accessor read is checked here against its buffer view and buffer
// (tinygltf does not), so a malformed file gives an error naming its JSON
// pointer, never a read out of bounds. Textures are not decoded (the image
// callback accepts them without reading pixels). Buffer and image files are
// read only from inside the glTF file's own folder, and only when they are
// regular files (a FIFO would block, a directory cannot be read).
#include "formats/gltf_module.h"

#include <tiny_gltf.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

extern "C" {
#include "base/error.h"
}

namespace {

// Limits (docs/ROBUSTNESS.md's, for meshes): beyond them a file is refused.
const uint64_t max_elements = uint64_t(1) << 28;

struct failure {
    rt_status status;
    std::string text;
};

[[noreturn]] void fail(const std::string &where, const std::string &what,
                       rt_status st = RT_ERROR_PARSE) {
    throw failure{st, where.empty() ? what : where + ": " + what};
}

std::string ptr(const char *kind, size_t i) {
    return std::string("/") + kind + "/" + std::to_string(i);
}

template <class T> T *c_array(const std::vector<T> &v) {
    if (v.empty()) return nullptr;
    T *p = static_cast<T *>(std::malloc(v.size() * sizeof(T)));
    if (!p) throw std::bad_alloc();
    std::memcpy(p, v.data(), v.size() * sizeof(T));
    return p;
}

template <class T> T *c_calloc(size_t n) {
    if (!n) return nullptr;
    T *p = static_cast<T *>(std::calloc(n, sizeof(T)));
    if (!p) throw std::bad_alloc();
    return p;
}

void copy_name(char *dst, size_t size, const std::string &src) {
    std::snprintf(dst, size, "%s", src.c_str());
}

// ---- file access: the folder of the glTF file only --------------------------

struct fs_context {
    std::string folder; // realpath of the file's folder
};

bool fs_exists(const std::string &path, void *) {
    struct stat st;
    return ::stat(path.c_str(), &st) == 0;
}

std::string fs_expand(const std::string &path, void *) {
    return path;
}

bool fs_read(std::vector<unsigned char> *out, std::string *err, const std::string &path,
             void *user) {
    const fs_context *ctx = static_cast<const fs_context *>(user);
    char *real = ::realpath(path.c_str(), nullptr);
    if (!real) {
        if (err) *err = std::string("cannot be found: ") + std::strerror(errno);
        return false;
    }
    std::string r(real);
    std::free(real);
    if (r.size() <= ctx->folder.size() + 1 || r.compare(0, ctx->folder.size(), ctx->folder) != 0 ||
        (ctx->folder != "/" && r[ctx->folder.size()] != '/')) {
        if (err) *err = "the URI leaves the glTF file's folder (" + ctx->folder + "): refused";
        return false;
    }
    // O_NONBLOCK: a FIFO must not block the open; fstat then refuses it.
    int fd = ::open(r.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (err) *err = std::string("cannot be opened: ") + std::strerror(errno);
        return false;
    }
    struct stat st;
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        if (err) *err = "not a regular file (a directory, FIFO or device): refused";
        return false;
    }
    if (static_cast<uint64_t>(st.st_size) > (uint64_t(1) << 32)) {
        ::close(fd);
        if (err) *err = "larger than 4 GiB: refused";
        return false;
    }
    out->resize(static_cast<size_t>(st.st_size));
    size_t got = 0;
    while (got < out->size()) {
        ssize_t n = ::read(fd, out->data() + got, out->size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            ::close(fd);
            if (err) *err = "read error";
            return false;
        }
        got += static_cast<size_t>(n);
    }
    ::close(fd);
    return true;
}

bool fs_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *) {
    if (err) *err = "writing is not supported";
    return false;
}

// Textures: accepted, never decoded (the renderer has no textures).
bool skip_image(tinygltf::Image *, const int, std::string *, std::string *, int, int,
                const unsigned char *, int, void *) {
    return true;
}

// ---- accessors --------------------------------------------------------------

int component_size(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return 4;
    default:
        return 0;
    }
}

int type_components(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return 1;
    case TINYGLTF_TYPE_VEC2:
        return 2;
    case TINYGLTF_TYPE_VEC3:
        return 3;
    case TINYGLTF_TYPE_VEC4:
        return 4;
    case TINYGLTF_TYPE_MAT2:
        return 4;
    case TINYGLTF_TYPE_MAT3:
        return 9;
    case TINYGLTF_TYPE_MAT4:
        return 16;
    default:
        return 0;
    }
}

// One component at p as a double: normalized integers to [0,1] or [-1,1]
// (the specification's rule: max(c / max, -1)), other integers as they are.
double read_component(const unsigned char *p, int type, bool normalized) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        int8_t v;
        std::memcpy(&v, p, 1);
        return normalized ? std::fmax(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::fmax(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return normalized ? v / 4294967295.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    }
    return 0.0;
}

struct view_span {
    const unsigned char *base;
    uint64_t length;
    uint64_t stride; // 0: tightly packed
};

view_span get_view(const tinygltf::Model &m, int index, const std::string &where) {
    if (index < 0 || static_cast<size_t>(index) >= m.bufferViews.size())
        fail(where, "bufferView " + std::to_string(index) + " does not exist");
    const tinygltf::BufferView &v = m.bufferViews[static_cast<size_t>(index)];
    std::string vw = ptr("bufferViews", static_cast<size_t>(index));
    if (v.buffer < 0 || static_cast<size_t>(v.buffer) >= m.buffers.size())
        fail(vw, "buffer " + std::to_string(v.buffer) + " does not exist");
    const tinygltf::Buffer &b = m.buffers[static_cast<size_t>(v.buffer)];
    uint64_t off = v.byteOffset, len = v.byteLength;
    if (off > b.data.size() || len > b.data.size() - off)
        fail(vw, "bytes " + std::to_string(off) + " .. " + std::to_string(off + len) +
                     " lie outside buffer " + std::to_string(v.buffer) + " (" +
                     std::to_string(b.data.size()) + " bytes)");
    if (v.byteStride != 0 && (v.byteStride < 4 || v.byteStride > 252))
        fail(vw, "byteStride " + std::to_string(v.byteStride) + " is not in 4..252");
    return {b.data.data() + off, len, v.byteStride};
}

// Reads count elements of n components from a view at offset into out
// (count * n doubles), checking every byte lies inside the view.
void read_elements(const view_span &span, uint64_t offset, uint64_t count, int n, int ctype,
                   bool normalized, const std::string &where, std::vector<double> &out,
                   bool sparse_values) {
    int cs = component_size(ctype);
    uint64_t elem = static_cast<uint64_t>(cs) * static_cast<uint64_t>(n);
    uint64_t stride = span.stride && !sparse_values ? span.stride : elem;
    if (count) {
        uint64_t last = offset + stride * (count - 1) + elem;
        if (offset > span.length || last > span.length ||
            stride * (count - 1) / stride != count - 1)
            fail(where, "reads bytes up to " + std::to_string(last) + " of a bufferView of " +
                            std::to_string(span.length) + " bytes (out of bounds)");
    }
    out.resize(static_cast<size_t>(count * static_cast<uint64_t>(n)));
    for (uint64_t i = 0; i < count; i++) {
        const unsigned char *p = span.base + offset + stride * i;
        for (int c = 0; c < n; c++)
            out[static_cast<size_t>(i * static_cast<uint64_t>(n) + static_cast<uint64_t>(c))] =
                read_component(p + c * cs, ctype, normalized);
    }
}

struct decoded {
    uint64_t count = 0;
    int components = 0;
    std::vector<double> values;
};

decoded read_accessor(const tinygltf::Model &m, int index, const std::string &user) {
    if (index < 0 || static_cast<size_t>(index) >= m.accessors.size())
        fail(user, "accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor &a = m.accessors[static_cast<size_t>(index)];
    std::string where = ptr("accessors", static_cast<size_t>(index));
    int n = type_components(a.type), cs = component_size(a.componentType);
    if (!n) fail(where, "unknown type");
    if (!cs) fail(where, "componentType " + std::to_string(a.componentType) + " is not allowed");
    if (a.count > max_elements)
        fail(where, "count " + std::to_string(a.count) + " is more than 2^28",
             RT_ERROR_UNSUPPORTED);
    if (n > 4 && a.type != TINYGLTF_TYPE_MAT4)
        fail(where, "matrix accessors other than MAT4 are not supported", RT_ERROR_UNSUPPORTED);
    decoded d;
    d.count = a.count;
    d.components = n;
    if (a.bufferView >= 0) {
        view_span span = get_view(m, a.bufferView, where);
        if (a.byteOffset % static_cast<size_t>(cs) != 0)
            fail(where, "byteOffset is not a multiple of the component size");
        read_elements(span, a.byteOffset, a.count, n, a.componentType, a.normalized, where,
                      d.values, false);
    } else {
        // Zeros (and sparse values): nothing in the file bounds the count.
        if (a.count * static_cast<uint64_t>(n) > (uint64_t(1) << 24))
            fail(where, "an accessor without a bufferView of more than 2^24 values",
                 RT_ERROR_UNSUPPORTED);
        d.values.assign(static_cast<size_t>(a.count * static_cast<uint64_t>(n)), 0.0);
    }
    if (a.sparse.isSparse) {
        std::string sw = where + "/sparse";
        if (a.sparse.count < 1 || static_cast<uint64_t>(a.sparse.count) > a.count)
            fail(sw, "count " + std::to_string(a.sparse.count) + " is not in 1.." +
                         std::to_string(a.count));
        int it = a.sparse.indices.componentType;
        if (it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(sw + "/indices", "componentType must be an unsigned integer type");
        std::vector<double> idx, val;
        uint64_t sc = static_cast<uint64_t>(a.sparse.count);
        if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
            fail(sw, "negative byteOffset");
        read_elements(get_view(m, a.sparse.indices.bufferView, sw + "/indices"),
                      static_cast<uint64_t>(a.sparse.indices.byteOffset), sc, 1, it, false,
                      sw + "/indices", idx, true);
        read_elements(get_view(m, a.sparse.values.bufferView, sw + "/values"),
                      static_cast<uint64_t>(a.sparse.values.byteOffset), sc, n, a.componentType,
                      a.normalized, sw + "/values", val, true);
        for (uint64_t i = 0; i < sc; i++) {
            double k = idx[static_cast<size_t>(i)];
            if (k >= static_cast<double>(a.count))
                fail(sw + "/indices", "index " + std::to_string(static_cast<uint64_t>(k)) +
                                          " is not below the accessor's count " +
                                          std::to_string(a.count));
            if (i && k <= idx[static_cast<size_t>(i - 1)])
                fail(sw + "/indices", "indices are not strictly increasing");
            for (int c = 0; c < n; c++)
                d.values[static_cast<size_t>(static_cast<uint64_t>(k) * static_cast<uint64_t>(n) +
                                             static_cast<uint64_t>(c))] =
                    val[static_cast<size_t>(i * static_cast<uint64_t>(n) +
                                            static_cast<uint64_t>(c))];
        }
    }
    return d;
}

std::vector<float> as_floats(const decoded &d, const std::string &where, bool finite = true) {
    std::vector<float> f(d.values.size());
    for (size_t i = 0; i < f.size(); i++) {
        f[i] = static_cast<float>(d.values[i]);
        if (finite && !std::isfinite(f[i]))
            fail(where, "value " + std::to_string(i) + " is not a finite float");
    }
    return f;
}

decoded read_accessor_as(const tinygltf::Model &m, int index, int components,
                         const std::string &user, const char *what) {
    decoded d = read_accessor(m, index, user);
    if (d.components != components)
        fail(ptr("accessors", static_cast<size_t>(index)),
             std::string(what) + " needs " + std::to_string(components) +
                 " components per element, the accessor has " + std::to_string(d.components));
    return d;
}

// ---- the document -----------------------------------------------------------

void free_doc(rt_gltf_doc *doc) {
    if (!doc) return;
    for (uint32_t i = 0; i < doc->node_count; i++) {
        std::free(doc->nodes[i].children);
        std::free(doc->nodes[i].weights);
    }
    for (uint32_t i = 0; i < doc->mesh_count; i++) {
        rt_gltf_mesh *me = &doc->meshes[i];
        for (uint32_t p = 0; p < me->prim_count; p++) {
            rt_gltf_prim *pr = &me->prims[p];
            std::free(pr->positions);
            std::free(pr->normals);
            std::free(pr->indices);
            std::free(pr->joints);
            std::free(pr->weights);
            std::free(pr->target_positions);
            std::free(pr->target_normals);
        }
        std::free(me->prims);
        std::free(me->weights);
    }
    for (uint32_t i = 0; i < doc->skin_count; i++) {
        std::free(doc->skins[i].joints);
        std::free(doc->skins[i].inverse_bind);
    }
    for (uint32_t i = 0; i < doc->animation_count; i++) {
        rt_gltf_animation *an = &doc->animations[i];
        for (uint32_t s = 0; s < an->sampler_count; s++) {
            std::free(an->samplers[s].times);
            std::free(an->samplers[s].values);
        }
        std::free(an->samplers);
        std::free(an->channels);
    }
    std::free(doc->nodes);
    std::free(doc->meshes);
    std::free(doc->skins);
    std::free(doc->animations);
    std::free(doc->materials);
    std::free(doc->cameras);
    std::free(doc->lights);
    std::free(doc->roots);
    std::free(doc);
}

int32_t index_or_none(int i) {
    return i < 0 ? RT_GLTF_NONE : static_cast<int32_t>(i);
}

void convert_prim(const tinygltf::Model &m, const tinygltf::Primitive &p, const std::string &where,
                  rt_gltf_prim *out) {
    out->material = index_or_none(p.material);
    auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) fail(where + "/attributes", "no POSITION");
    decoded dp = read_accessor_as(m, pos->second, 3, where + "/attributes/POSITION", "POSITION");
    uint64_t nv = dp.count;
    out->vertex_count = static_cast<uint32_t>(nv);
    out->positions = c_array(as_floats(dp, ptr("accessors", static_cast<size_t>(pos->second))));
    auto nrm = p.attributes.find("NORMAL");
    if (nrm != p.attributes.end()) {
        decoded dn = read_accessor_as(m, nrm->second, 3, where + "/attributes/NORMAL", "NORMAL");
        if (dn.count != nv) fail(where + "/attributes/NORMAL", "count differs from POSITION's");
        out->normals = c_array(as_floats(dn, ptr("accessors", static_cast<size_t>(nrm->second))));
    }
    // Indices (or 0..n-1), then strips and fans as lists.
    std::vector<uint32_t> idx;
    if (p.indices >= 0) {
        decoded di = read_accessor(m, p.indices, where + "/indices");
        const tinygltf::Accessor &a = m.accessors[static_cast<size_t>(p.indices)];
        if (di.components != 1 || a.normalized ||
            (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
             a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
             a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
            fail(ptr("accessors", static_cast<size_t>(p.indices)),
                 "indices must be unsigned integer scalars");
        idx.resize(di.values.size());
        for (size_t i = 0; i < idx.size(); i++) idx[i] = static_cast<uint32_t>(di.values[i]);
    } else {
        idx.resize(static_cast<size_t>(nv));
        for (size_t i = 0; i < idx.size(); i++) idx[i] = static_cast<uint32_t>(i);
    }
    std::vector<uint32_t> tri;
    if (p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == -1) {
        tri.assign(idx.begin(), idx.begin() + static_cast<long>(idx.size() / 3 * 3));
    } else if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 2; i < idx.size(); i++) {
            // Every second triangle flipped, so that all keep the first's winding.
            if (i % 2 == 0)
                tri.insert(tri.end(), {idx[i - 2], idx[i - 1], idx[i]});
            else
                tri.insert(tri.end(), {idx[i - 1], idx[i - 2], idx[i]});
        }
    } else if (p.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (size_t i = 2; i < idx.size(); i++) tri.insert(tri.end(), {idx[i - 1], idx[i], idx[0]});
    }
    out->triangle_count = static_cast<uint32_t>(tri.size() / 3);
    out->indices = c_array(tri);
    // Joints and weights, sets 0 and 1, interleaved: per vertex set 0's four
    // then set 1's four.
    std::vector<uint32_t> joints;
    std::vector<float> weights;
    uint32_t sets = 0;
    while (sets < 2 && p.attributes.count("JOINTS_" + std::to_string(sets)) &&
           p.attributes.count("WEIGHTS_" + std::to_string(sets)))
        sets++;
    out->joint_sets = sets;
    joints.resize(static_cast<size_t>(nv) * 4 * sets);
    weights.resize(joints.size());
    for (uint32_t set = 0; set < sets; set++) {
        int ja = p.attributes.at("JOINTS_" + std::to_string(set));
        int wa = p.attributes.at("WEIGHTS_" + std::to_string(set));
        decoded dj = read_accessor_as(m, ja, 4, where + "/attributes/JOINTS_" + std::to_string(set),
                                      "JOINTS");
        decoded dw = read_accessor_as(
            m, wa, 4, where + "/attributes/WEIGHTS_" + std::to_string(set), "WEIGHTS");
        if (dj.count != nv || dw.count != nv)
            fail(where + "/attributes", "JOINTS_" + std::to_string(set) + " or WEIGHTS_" +
                                            std::to_string(set) + " count differs from POSITION's");
        std::vector<float> wf = as_floats(dw, ptr("accessors", static_cast<size_t>(wa)));
        for (size_t v = 0; v < static_cast<size_t>(nv); v++)
            for (size_t c = 0; c < 4; c++) {
                size_t dst = v * 4 * sets + set * 4 + c;
                double jv = dj.values[v * 4 + c];
                joints[dst] = jv >= 0 && jv < 4294967295.0 ? static_cast<uint32_t>(jv) : UINT32_MAX;
                weights[dst] = wf[v * 4 + c];
            }
    }
    out->joints = c_array(joints);
    out->weights = c_array(weights);
    // Morph targets.
    if (!p.targets.empty()) {
        size_t nt = p.targets.size();
        if (nt > 1024)
            fail(where + "/targets", "more than 1024 morph targets", RT_ERROR_UNSUPPORTED);
        if (static_cast<uint64_t>(nt) * nv > (uint64_t(1) << 26))
            fail(where + "/targets", "morph targets x vertices above 2^26", RT_ERROR_UNSUPPORTED);
        out->target_count = static_cast<uint32_t>(nt);
        bool any_normal = false;
        for (const auto &t : p.targets)
            if (t.count("NORMAL")) any_normal = true;
        out->target_positions = c_calloc<float>(nt * 3 * static_cast<size_t>(nv));
        if (any_normal && out->normals)
            out->target_normals = c_calloc<float>(nt * 3 * static_cast<size_t>(nv));
        for (size_t t = 0; t < nt; t++) {
            std::string tw = where + "/targets/" + std::to_string(t);
            for (int which = 0; which < 2; which++) {
                const char *name = which ? "NORMAL" : "POSITION";
                float *dst = which ? out->target_normals : out->target_positions;
                auto a = p.targets[t].find(name);
                if (a == p.targets[t].end() || !dst) continue;
                decoded dd = read_accessor_as(m, a->second, 3, tw + "/" + name, name);
                if (dd.count != nv) fail(tw + "/" + name, "count differs from POSITION's");
                std::vector<float> f =
                    as_floats(dd, ptr("accessors", static_cast<size_t>(a->second)));
                std::memcpy(dst + t * 3 * static_cast<size_t>(nv), f.data(),
                            f.size() * sizeof(float));
            }
        }
    }
}

std::vector<float> weights_of(const std::vector<double> &w) {
    std::vector<float> f(w.size());
    for (size_t i = 0; i < w.size(); i++) f[i] = static_cast<float>(w[i]);
    return f;
}

void convert(const tinygltf::Model &m, rt_gltf_doc *doc) {
    // Nodes.
    doc->node_count = static_cast<uint32_t>(m.nodes.size());
    doc->nodes = c_calloc<rt_gltf_node>(m.nodes.size());
    for (size_t i = 0; i < m.nodes.size(); i++) {
        const tinygltf::Node &n = m.nodes[i];
        rt_gltf_node *o = &doc->nodes[i];
        std::string w = ptr("nodes", i);
        copy_name(o->name, sizeof o->name, n.name);
        o->mesh = index_or_none(n.mesh);
        o->skin = index_or_none(n.skin);
        o->camera = index_or_none(n.camera);
        o->light = RT_GLTF_NONE;
        auto ext = n.extensions.find("KHR_lights_punctual");
        if (ext != n.extensions.end() && ext->second.IsObject() && ext->second.Has("light")) {
            const tinygltf::Value &l = ext->second.Get("light");
            if (l.IsNumber() || l.IsInt()) o->light = index_or_none(l.GetNumberAsInt());
        }
        o->translation[0] = o->translation[1] = o->translation[2] = 0.0;
        o->rotation[0] = o->rotation[1] = o->rotation[2] = 0.0;
        o->rotation[3] = 1.0;
        o->scale[0] = o->scale[1] = o->scale[2] = 1.0;
        if (!n.matrix.empty()) {
            if (n.matrix.size() != 16) fail(w + "/matrix", "not 16 numbers");
            o->has_matrix = 1;
            for (int k = 0; k < 16; k++) o->matrix[k] = n.matrix[static_cast<size_t>(k)];
        }
        if (!n.translation.empty()) {
            if (n.translation.size() != 3) fail(w + "/translation", "not 3 numbers");
            for (int k = 0; k < 3; k++) o->translation[k] = n.translation[static_cast<size_t>(k)];
        }
        if (!n.rotation.empty()) {
            if (n.rotation.size() != 4) fail(w + "/rotation", "not 4 numbers");
            for (int k = 0; k < 4; k++) o->rotation[k] = n.rotation[static_cast<size_t>(k)];
        }
        if (!n.scale.empty()) {
            if (n.scale.size() != 3) fail(w + "/scale", "not 3 numbers");
            for (int k = 0; k < 3; k++) o->scale[k] = n.scale[static_cast<size_t>(k)];
        }
        std::vector<int32_t> ch(n.children.begin(), n.children.end());
        o->child_count = static_cast<uint32_t>(ch.size());
        o->children = c_array(ch);
        std::vector<float> nw = weights_of(n.weights);
        o->weight_count = static_cast<uint32_t>(nw.size());
        o->weights = c_array(nw);
    }
    // Meshes.
    doc->mesh_count = static_cast<uint32_t>(m.meshes.size());
    doc->meshes = c_calloc<rt_gltf_mesh>(m.meshes.size());
    for (size_t i = 0; i < m.meshes.size(); i++) {
        const tinygltf::Mesh &me = m.meshes[i];
        rt_gltf_mesh *o = &doc->meshes[i];
        copy_name(o->name, sizeof o->name, me.name);
        std::vector<float> mw = weights_of(me.weights);
        o->weight_count = static_cast<uint32_t>(mw.size());
        o->weights = c_array(mw);
        o->prims = c_calloc<rt_gltf_prim>(me.primitives.size());
        for (size_t p = 0; p < me.primitives.size(); p++) {
            int mode = me.primitives[p].mode;
            if (mode != -1 && mode != TINYGLTF_MODE_TRIANGLES &&
                mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                o->skipped_prims++;
                continue;
            }
            // Counted first, so that a failure part-way is freed with the rest.
            rt_gltf_prim *pr = &o->prims[o->prim_count++];
            convert_prim(m, me.primitives[p], ptr("meshes", i) + "/primitives/" + std::to_string(p),
                         pr);
        }
    }
    // Skins.
    doc->skin_count = static_cast<uint32_t>(m.skins.size());
    doc->skins = c_calloc<rt_gltf_skin>(m.skins.size());
    for (size_t i = 0; i < m.skins.size(); i++) {
        const tinygltf::Skin &s = m.skins[i];
        rt_gltf_skin *o = &doc->skins[i];
        std::vector<int32_t> j(s.joints.begin(), s.joints.end());
        o->joint_count = static_cast<uint32_t>(j.size());
        o->joints = c_array(j);
        std::vector<double> ib(j.size() * 16, 0.0);
        for (size_t k = 0; k < j.size(); k++)
            for (int d = 0; d < 4; d++) ib[k * 16 + static_cast<size_t>(d) * 5] = 1.0;
        if (s.inverseBindMatrices >= 0) {
            decoded d = read_accessor_as(m, s.inverseBindMatrices, 16,
                                         ptr("skins", i) + "/inverseBindMatrices", "MAT4");
            if (d.count < j.size())
                fail(ptr("skins", i) + "/inverseBindMatrices", "fewer matrices than joints");
            for (size_t k = 0; k < ib.size(); k++) {
                ib[k] = static_cast<double>(static_cast<float>(d.values[k]));
                if (!std::isfinite(ib[k]))
                    fail(ptr("skins", i) + "/inverseBindMatrices", "a value is not finite");
            }
        }
        o->inverse_bind = c_array(ib);
    }
    // Animations.
    doc->animation_count = static_cast<uint32_t>(m.animations.size());
    doc->animations = c_calloc<rt_gltf_animation>(m.animations.size());
    for (size_t i = 0; i < m.animations.size(); i++) {
        const tinygltf::Animation &an = m.animations[i];
        rt_gltf_animation *o = &doc->animations[i];
        copy_name(o->name, sizeof o->name, an.name);
        o->channel_count = static_cast<uint32_t>(an.channels.size());
        o->channels = c_calloc<rt_gltf_channel>(an.channels.size());
        for (size_t c = 0; c < an.channels.size(); c++) {
            const tinygltf::AnimationChannel &ch = an.channels[c];
            rt_gltf_channel *oc = &o->channels[c];
            oc->node = index_or_none(ch.target_node);
            oc->sampler = ch.sampler < 0 ? RT_GLTF_NONE : ch.sampler;
            const std::string &p = ch.target_path;
            oc->path = p == "translation" ? RT_GLTF_PATH_TRANSLATION
                       : p == "rotation"  ? RT_GLTF_PATH_ROTATION
                       : p == "scale"     ? RT_GLTF_PATH_SCALE
                       : p == "weights"   ? RT_GLTF_PATH_WEIGHTS
                                          : -1;
        }
        o->sampler_count = static_cast<uint32_t>(an.samplers.size());
        o->samplers = c_calloc<rt_gltf_sampler>(an.samplers.size());
        for (size_t s = 0; s < an.samplers.size(); s++) {
            const tinygltf::AnimationSampler &sa = an.samplers[s];
            rt_gltf_sampler *os = &o->samplers[s];
            std::string w = ptr("animations", i) + "/samplers/" + std::to_string(s);
            copy_name(os->where, sizeof os->where, w);
            os->interpolation = sa.interpolation == "STEP"          ? RT_GLTF_STEP
                                : sa.interpolation == "CUBICSPLINE" ? RT_GLTF_CUBICSPLINE
                                                                    : RT_GLTF_LINEAR;
            if (!sa.interpolation.empty() && sa.interpolation != "LINEAR" &&
                sa.interpolation != "STEP" && sa.interpolation != "CUBICSPLINE")
                fail(w + "/interpolation", "unknown interpolation '" + sa.interpolation + "'");
            decoded din = read_accessor_as(m, sa.input, 1, w + "/input", "an animation input");
            decoded dout = read_accessor(m, sa.output, w + "/output");
            // Times and values are checked for NaN and order by the library
            // (gltf_load.c), with this sampler's pointer.
            std::vector<float> t = as_floats(din, w + "/input", false);
            std::vector<float> v = as_floats(dout, w + "/output", false);
            os->key_count = static_cast<uint32_t>(din.count);
            os->times = c_array(t);
            os->value_count = static_cast<uint32_t>(dout.count);
            os->components = static_cast<uint32_t>(dout.components);
            os->values = c_array(v);
        }
    }
    // Materials.
    doc->material_count = static_cast<uint32_t>(m.materials.size());
    doc->materials = c_calloc<rt_gltf_material>(m.materials.size());
    for (size_t i = 0; i < m.materials.size(); i++) {
        const tinygltf::Material &ma = m.materials[i];
        rt_gltf_material *o = &doc->materials[i];
        const auto &pbr = ma.pbrMetallicRoughness;
        for (int k = 0; k < 4; k++)
            o->base_color[k] = static_cast<size_t>(k) < pbr.baseColorFactor.size()
                                   ? pbr.baseColorFactor[static_cast<size_t>(k)]
                                   : 1.0;
        o->metallic = pbr.metallicFactor;
        o->roughness = pbr.roughnessFactor;
        for (int k = 0; k < 3; k++)
            o->emissive[k] = static_cast<size_t>(k) < ma.emissiveFactor.size()
                                 ? ma.emissiveFactor[static_cast<size_t>(k)]
                                 : 0.0;
        o->textured = pbr.baseColorTexture.index >= 0 || pbr.metallicRoughnessTexture.index >= 0 ||
                      ma.normalTexture.index >= 0 || ma.occlusionTexture.index >= 0 ||
                      ma.emissiveTexture.index >= 0;
    }
    // Cameras and lights.
    doc->camera_count = static_cast<uint32_t>(m.cameras.size());
    doc->cameras = c_calloc<rt_gltf_camera>(m.cameras.size());
    for (size_t i = 0; i < m.cameras.size(); i++) {
        doc->cameras[i].perspective = m.cameras[i].type == "perspective";
        doc->cameras[i].yfov = m.cameras[i].perspective.yfov;
        doc->cameras[i].aspect = m.cameras[i].perspective.aspectRatio;
    }
    doc->light_count = static_cast<uint32_t>(m.lights.size());
    doc->lights = c_calloc<rt_gltf_light>(m.lights.size());
    for (size_t i = 0; i < m.lights.size(); i++) {
        const tinygltf::Light &l = m.lights[i];
        rt_gltf_light *o = &doc->lights[i];
        o->type = l.type == "point"         ? RT_GLTF_LIGHT_POINT
                  : l.type == "spot"        ? RT_GLTF_LIGHT_SPOT
                  : l.type == "directional" ? RT_GLTF_LIGHT_DIRECTIONAL
                                            : RT_GLTF_LIGHT_OTHER;
        for (int k = 0; k < 3; k++)
            o->color[k] =
                static_cast<size_t>(k) < l.color.size() ? l.color[static_cast<size_t>(k)] : 1.0;
        o->intensity = l.intensity;
    }
    doc->texture_count = static_cast<uint32_t>(m.textures.size());
    // The scene.
    std::vector<int32_t> roots;
    if (!m.scenes.empty()) {
        size_t s = m.defaultScene >= 0 ? static_cast<size_t>(m.defaultScene) : 0;
        if (s >= m.scenes.size()) fail("/scene", "scene " + std::to_string(s) + " does not exist");
        roots.assign(m.scenes[s].nodes.begin(), m.scenes[s].nodes.end());
    } else {
        // No scene: every node that is no child is a root.
        std::vector<char> child(m.nodes.size(), 0);
        for (const auto &n : m.nodes)
            for (int c : n.children)
                if (c >= 0 && static_cast<size_t>(c) < child.size())
                    child[static_cast<size_t>(c)] = 1;
        for (size_t i = 0; i < m.nodes.size(); i++)
            if (!child[i]) roots.push_back(static_cast<int32_t>(i));
    }
    doc->root_count = static_cast<uint32_t>(roots.size());
    doc->roots = c_array(roots);
}

std::string one_line(std::string t) {
    while (!t.empty() && (t.back() == '\n' || t.back() == '\r' || t.back() == ' ')) t.pop_back();
    for (char &c : t)
        if (c == '\n' || c == '\r') c = ';';
    return t;
}

bool has_ext(const char *path, const char *ext) {
    size_t n = std::strlen(path), e = std::strlen(ext);
    if (n < e) return false;
    for (size_t i = 0; i < e; i++) {
        char c = path[n - e + i];
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
        if (c != ext[i]) return false;
    }
    return true;
}

uint32_t le32(const std::vector<unsigned char> &b, size_t at) {
    return static_cast<uint32_t>(b[at]) | static_cast<uint32_t>(b[at + 1]) << 8 |
           static_cast<uint32_t>(b[at + 2]) << 16 | static_cast<uint32_t>(b[at + 3]) << 24;
}

// What is wrong with a .glb container (header, chunk lengths), or "".
std::string glb_problem(const std::vector<unsigned char> &b) {
    if (b.size() < 12)
        return "not a glTF binary: " + std::to_string(b.size()) + " bytes, no header";
    if (le32(b, 0) != 0x46546C67u) return "not a glTF binary (no 'glTF' magic)";
    if (le32(b, 4) != 2) return "glTF binary version " + std::to_string(le32(b, 4)) + ", not 2";
    uint64_t total = le32(b, 8);
    if (total > b.size())
        return "truncated glTF binary: its header says " + std::to_string(total) +
               " bytes, the file has " + std::to_string(b.size());
    size_t end = static_cast<size_t>(total), at = 12;
    for (int chunk = 0; at < end; chunk++) {
        if (end - at < 8)
            return "glTF binary chunk " + std::to_string(chunk) + " at byte " + std::to_string(at) +
                   ": its header is cut";
        uint64_t len = le32(b, at);
        if (len > end - at - 8)
            return "glTF binary chunk " + std::to_string(chunk) + " at byte " + std::to_string(at) +
                   ": " + std::to_string(len) + " bytes announced, " +
                   std::to_string(end - at - 8) + " left (truncated)";
        if (chunk == 0 && le32(b, at + 4) != 0x4E4F534Au)
            return "glTF binary: the first chunk is not JSON";
        at += 8 + static_cast<size_t>(len);
    }
    return "";
}

rt_status read_doc(const char *path, rt_gltf_doc **out, rt_error *err) {
    *out = nullptr;
    rt_gltf_doc *doc = nullptr;
    try {
        // The file itself must be a regular file too (not a FIFO).
        struct stat st;
        if (::stat(path, &st) != 0)
            return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "cannot be opened: %s",
                                std::strerror(errno));
        if (!S_ISREG(st.st_mode))
            return rt_error_set(err, RT_ERROR_IO, path, 0, 0,
                                "not a regular file (a directory, FIFO or device)");
        std::string p(path);
        size_t slash = p.rfind('/');
        std::string folder =
            slash == std::string::npos ? "." : (slash == 0 ? "/" : p.substr(0, slash));
        char *real = ::realpath(folder.c_str(), nullptr);
        if (!real)
            return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "its folder cannot be resolved: %s",
                                std::strerror(errno));
        fs_context ctx;
        ctx.folder = real;
        std::free(real);
        tinygltf::FsCallbacks fs;
        fs.FileExists = fs_exists;
        fs.ExpandFilePath = fs_expand;
        fs.ReadWholeFile = fs_read;
        fs.WriteWholeFile = fs_write;
        fs.user_data = &ctx;

        tinygltf::TinyGLTF loader;
        loader.SetFsCallbacks(fs);
        loader.SetImageLoader(skip_image, nullptr);
        tinygltf::Model model;
        std::string terr, twarn;
        // Read through our checked reader, then parse from memory.
        std::vector<unsigned char> bytes;
        std::string rerr;
        fs_context any;
        any.folder = "/";
        if (!fs_read(&bytes, &rerr, path, &any))
            return rt_error_set(err, RT_ERROR_IO, path, 0, 0, "%s", rerr.c_str());
        if (has_ext(path, ".glb")) {
            // The container first, so that a cut or damaged file says how.
            std::string why = glb_problem(bytes);
            if (!why.empty())
                return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, "%s", why.c_str());
        }
        bool ok;
        if (has_ext(path, ".glb"))
            ok = loader.LoadBinaryFromMemory(&model, &terr, &twarn, bytes.data(),
                                             static_cast<unsigned int>(bytes.size()), ctx.folder);
        else
            ok = loader.LoadASCIIFromString(&model, &terr, &twarn,
                                            reinterpret_cast<const char *>(bytes.data()),
                                            static_cast<unsigned int>(bytes.size()), ctx.folder);
        if (!ok)
            return rt_error_set(
                err, RT_ERROR_PARSE, path, 0, 0, "%s",
                one_line(terr.empty() ? "tinygltf could not read it" : terr).c_str());
        // tinygltf reports a buffer it could not load as a warning on some
        // paths; a buffer without its bytes is an error here.
        for (size_t b = 0; b < model.buffers.size(); b++)
            if (model.buffers[b].data.empty())
                return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, "/buffers/%zu: no data (%s)",
                                    b, one_line(twarn.empty() ? "empty" : twarn).c_str());
        // A required extension this loader does not know could change the
        // geometry (Draco or meshopt compression, GPU instancing): refused.
        for (size_t e = 0; e < model.extensionsRequired.size(); e++) {
            const std::string &x = model.extensionsRequired[e];
            bool safe = x == "KHR_lights_punctual" || x == "KHR_mesh_quantization" ||
                        x == "KHR_texture_transform" || x == "KHR_texture_basisu" ||
                        x == "EXT_texture_webp" || x.compare(0, 14, "KHR_materials_") == 0;
            if (!safe)
                return rt_error_set(err, RT_ERROR_UNSUPPORTED, path, 0, 0,
                                    "/extensionsRequired/%zu: the file requires %s, which this "
                                    "loader does not support",
                                    e, x.c_str());
        }
        doc = static_cast<rt_gltf_doc *>(std::calloc(1, sizeof *doc));
        if (!doc) throw std::bad_alloc();
        convert(model, doc);
        std::snprintf(doc->warnings, sizeof doc->warnings, "%s", one_line(twarn).c_str());
        *out = doc;
        return RT_OK;
    } catch (const failure &f) {
        free_doc(doc);
        return rt_error_set(err, f.status, path, 0, 0, "%s", f.text.c_str());
    } catch (const std::bad_alloc &) {
        free_doc(doc);
        return rt_error_set(err, RT_ERROR_OUT_OF_MEMORY, path, 0, 0, "out of memory");
    } catch (const std::exception &e) {
        free_doc(doc);
        return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, "%s", e.what());
    } catch (...) {
        free_doc(doc);
        return rt_error_set(err, RT_ERROR_PARSE, path, 0, 0, "unreadable glTF");
    }
}

const rt_gltf_module table = {
    RT_GLTF_MODULE_ABI, sizeof(rt_gltf_doc), sizeof(rt_error), "tinygltf 2.7", read_doc, free_doc};

} // namespace

extern "C" __attribute__((visibility("default"))) const rt_gltf_module *rtcl_gltf_module(void) {
    return &table;
}
