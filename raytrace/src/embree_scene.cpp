// Embree 3 scenes of the radiosity mesh's geometry elements: the opaque elements (geometry 0) in
// a scene of their own, which every query but transmittance() traces, and with the panes of
// glazing (geometry 1) in a second scene for transmittance(), whose occlusion filter multiplies
// each pane's T(θ) into the ray and lets it go on. Device and scene live in move-only RAII handles;
// the device's error callback records the first error and the wrapper throws ExternalError after
// the failing call returns, as Embree's minimal.cpp tutorial recommends.

#include "raytrace/raytrace.h"

#include "core/error.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <tuple>
#include <utility>

namespace penumbra::raytrace {

namespace {

const char* error_name(RTCError code) {
    switch (code) {
    case RTC_ERROR_NONE:
        return "no error";
    case RTC_ERROR_UNKNOWN:
        return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
        return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
        return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
        return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
        return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
        return "cancelled";
    }
    return "unrecognised error code";
}

/// The first error Embree reported through the device callback since the last check.
class ErrorRecord {
public:
    static void callback(void* user, RTCError code, const char* message) {
        static_cast<ErrorRecord*>(user)->record(code, message);
    }

    /// Throws ExternalError naming \p call if an error was recorded, and clears it. Called
    /// after every trace by every thread: the flag spares them the lock (and its cache line)
    /// while nothing failed.
    void throw_if_failed(const char* call) {
        if (!failed_.load(std::memory_order_acquire))
            return;
        std::lock_guard lock(mutex_);
        if (code_ == RTC_ERROR_NONE)
            return;
        // Cleared only once the message is made: were making it to throw (out of memory),
        // the record would stay set and every later error be dropped.
        std::string text =
            fmt::format("Embree {} failed: {} ({})", call, message_, error_name(code_));
        code_ = RTC_ERROR_NONE;
        message_.clear();
        failed_.store(false, std::memory_order_relaxed);
        throw ExternalError(text);
    }

private:
    void record(RTCError code, const char* message) {
        std::lock_guard lock(mutex_);
        if (code_ != RTC_ERROR_NONE)
            return;
        code_ = code;
        message_ = message ? message : "";
        failed_.store(true, std::memory_order_release);
    }

    std::mutex mutex_;
    std::atomic<bool> failed_{false};
    RTCError code_ = RTC_ERROR_NONE;
    std::string message_;
};

/// Move-only owner of one Embree reference (device, scene or geometry).
template <typename Handle, void (*release)(Handle)> class Owned {
public:
    Owned() = default;
    explicit Owned(Handle h) : handle_(h) {}
    ~Owned() {
        if (handle_)
            release(handle_);
    }
    Owned(Owned&& o) noexcept : handle_(std::exchange(o.handle_, nullptr)) {}
    Owned& operator=(Owned&& o) noexcept {
        if (this != &o) {
            if (handle_)
                release(handle_);
            handle_ = std::exchange(o.handle_, nullptr);
        }
        return *this;
    }
    Owned(const Owned&) = delete;
    Owned& operator=(const Owned&) = delete;

    Handle get() const { return handle_; }

private:
    Handle handle_ = nullptr;
};

using DeviceHandle = Owned<RTCDevice, rtcReleaseDevice>;
using SceneHandle = Owned<RTCScene, rtcReleaseScene>;
using GeometryHandle = Owned<RTCGeometry, rtcReleaseGeometry>;

/// Rejects meshes whose indices would make Embree read out of bounds.
void check_mesh(const RadiosityMesh& mesh) {
    const std::size_t nv = mesh.vertex_count(), ne = mesh.element_count();
    if (mesh.element_patch.size() != ne || mesh.element_twin.size() != ne)
        throw InternalError("EmbreeScene: element arrays of the mesh differ in size");
    for (const auto& t : mesh.triangles)
        if (t[0] >= nv || t[1] >= nv || t[2] >= nv)
            throw InternalError("EmbreeScene: a triangle refers to a missing vertex");
    for (std::uint32_t e : mesh.geometry_elements)
        if (e >= ne || mesh.element_patch[e] >= mesh.patches.size())
            throw InternalError(fmt::format("EmbreeScene: geometry element {} is invalid", e));
    for (std::int32_t twin : mesh.element_twin)
        if (twin >= std::int32_t(ne))
            throw InternalError(fmt::format("EmbreeScene: twin element {} is invalid", twin));
}

RTCRay make_ray(const Vec3f& origin, const Vec3f& direction, float tnear, float tfar) {
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.tnear = tnear;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.time = 0.0f;
    ray.tfar = tfar;
    ray.mask = 0xffffffffu;
    ray.flags = 0;
    return ray;
}

/// Barycentrics (of vertices 1 and 2) of point \p p in the triangle (a, b, c), clamped into
/// the triangle against rounding.
std::pair<float, float> barycentrics(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    Vec3 n = cross(b - a, c - a);
    double area2 = dot(n, n);
    if (!(area2 > 0))
        return {0.0f, 0.0f};
    double w1 = std::max(0.0, dot(cross(p - a, c - a), n) / area2);
    double w2 = std::max(0.0, dot(cross(b - a, p - a), n) / area2);
    double sum = w1 + w2;
    if (sum > 1.0) {
        w1 /= sum;
        w2 /= sum;
    }
    return {float(w1), float(w2)};
}

} // namespace

// The rays traced, counted by every thread of the solver on every call: one shared counter
// bounced its cache line between the cores at each add. Each thread adds to a slot of its
// own (by the order threads first count, wrapping), on a line of its own.
class RayCount {
public:
    void add(std::uint64_t n) { slots_[slot()].n.fetch_add(n, std::memory_order_relaxed); }
    std::uint64_t total() const {
        std::uint64_t sum = 0;
        for (const Slot& s : slots_)
            sum += s.n.load(std::memory_order_relaxed);
        return sum;
    }

private:
    static constexpr std::size_t k_slots = 16;
    struct alignas(64) Slot {
        std::atomic<std::uint64_t> n{0};
    };
    static std::size_t slot() {
        static std::atomic<std::size_t> next{0};
        thread_local const std::size_t mine = next.fetch_add(1) % k_slots;
        return mine;
    }
    std::array<Slot, k_slots> slots_;
};

namespace {

/// What a ray met on its way through panes of glazing: the product of their T(θ) and the
/// surfaces counted, so that a pane reported twice (adjacent triangles at a shared edge, a
/// primitive split by the high-quality build) counts once.
constexpr std::size_t k_ray_batch = 256;

struct PaneCrossings {
    static constexpr int k_most = 8; ///< more distinct panes on one ray multiply uncounted
    float transmittance = 1.0f;
    int count = 0;
    std::array<std::uint32_t, k_most> surfaces{};

    /// \brief Counts surface \p s at \p t, unless it was counted already.
    void cross(std::uint32_t s, float t) {
        for (int i = 0; i < count; ++i)
            if (surfaces[std::size_t(i)] == s)
                return;
        if (count < k_most)
            surfaces[std::size_t(count++)] = s;
        transmittance *= t;
    }
};

/// The context of a transmittance() batch: Embree passes it to the panes' filter.
struct PaneContext {
    RTCIntersectContext base; // first, so that Embree's pointer to it is a PaneContext's
    const RadiosityMesh* mesh = nullptr;
    const std::vector<std::uint32_t>* panes = nullptr; ///< primitive → element
    PaneCrossings* crossings = nullptr;                ///< by ray id
};

/// The panes' occlusion filter: multiply the pane's T(θ) (the mean of its channels) into the
/// ray and reject the hit, so that traversal goes on to what lies behind.
void cross_pane(const RTCFilterFunctionNArguments* args) {
    const auto* context = reinterpret_cast<const PaneContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1)
            continue;
        args->valid[i] = 0;
        const std::uint32_t element = (*context->panes)[RTCHitN_primID(args->hit, args->N, i)];
        const Patch& patch = context->mesh->patch_of(element);
        const Vec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                       RTCRayN_dir_z(args->ray, args->N, i));
        const double cos_theta = std::abs(dot(normalize(dir), patch.normal));
        const Rgb t = patch.glazing->transmittance(cos_theta);
        context->crossings[RTCRayN_id(args->ray, args->N, i)].cross(patch.surface,
                                                                    (t.r + t.g + t.b) / 3.0f);
    }
}

} // namespace

struct EmbreeScene::Impl {
    // Declaration order is release order reversed: the scenes go before the device, and the
    // error record, which the device's callback points to, outlives both.
    ErrorRecord errors;
    DeviceHandle device;
    SceneHandle scene;                 ///< the opaque elements
    SceneHandle glazed_scene;          ///< the opaque elements and the panes; null without panes
    std::vector<std::uint32_t> opaque; ///< primitive of geometry 0 → element
    std::vector<std::uint32_t> panes;  ///< primitive of geometry 1 → element
    RayCount rays;

    void build(const RadiosityMesh& mesh);
    SceneHandle new_scene();
    GeometryHandle triangles(const RadiosityMesh& mesh, const std::vector<std::uint32_t>& elements);
};

void EmbreeScene::Impl::build(const RadiosityMesh& mesh) {
    device = DeviceHandle(rtcNewDevice(nullptr));
    if (!device.get())
        throw ExternalError(fmt::format("Embree rtcNewDevice failed ({}); check that the CPU "
                                        "supports SSE2 and that memory is available",
                                        error_name(rtcGetDeviceError(nullptr))));
    rtcSetDeviceErrorFunction(device.get(), &ErrorRecord::callback, &errors);

    for (std::uint32_t e : mesh.geometry_elements)
        (mesh.patch_of(e).opaque() ? opaque : panes).push_back(e);
    scene = new_scene();
    GeometryHandle walls = triangles(mesh, opaque);
    if (walls.get())
        rtcAttachGeometryByID(scene.get(), walls.get(), 0); // the scene keeps its own reference
    if (!panes.empty()) {
        glazed_scene = new_scene();
        if (walls.get())
            rtcAttachGeometryByID(glazed_scene.get(), walls.get(), 0);
        GeometryHandle glass = triangles(mesh, panes);
        rtcSetGeometryOccludedFilterFunction(glass.get(), &cross_pane);
        rtcAttachGeometryByID(glazed_scene.get(), glass.get(), 1);
        errors.throw_if_failed("rtcAttachGeometryByID");
        rtcCommitScene(glazed_scene.get());
    }
    errors.throw_if_failed("rtcAttachGeometryByID");
    rtcCommitScene(scene.get());
    errors.throw_if_failed("rtcCommitScene");
}

SceneHandle EmbreeScene::Impl::new_scene() {
    SceneHandle made(rtcNewScene(device.get()));
    errors.throw_if_failed("rtcNewScene");
    rtcSetSceneFlags(made.get(), RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(made.get(), RTC_BUILD_QUALITY_HIGH);
    errors.throw_if_failed("scene set-up");
    return made;
}

// A committed triangle geometry of \p elements (primitive p = elements[p]); none if empty.
GeometryHandle EmbreeScene::Impl::triangles(const RadiosityMesh& mesh,
                                            const std::vector<std::uint32_t>& elements) {
    if (elements.empty())
        return {};
    GeometryHandle geometry(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE));
    errors.throw_if_failed("rtcNewGeometry");
    rtcSetGeometryBuildQuality(geometry.get(), RTC_BUILD_QUALITY_HIGH);

    // Embree allocates these buffers itself, padded for its 16-byte loads; the mesh's own
    // arrays cannot be shared because they carry no padding and include the back sides.
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertex_count()));
    auto* indices = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(std::uint32_t), elements.size()));
    errors.throw_if_failed("rtcSetNewGeometryBuffer");

    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        vertices[3 * v + 0] = mesh.positions[v].x;
        vertices[3 * v + 1] = mesh.positions[v].y;
        vertices[3 * v + 2] = mesh.positions[v].z;
    }
    for (std::size_t p = 0; p < elements.size(); ++p) {
        const auto& t = mesh.triangles[elements[p]];
        std::copy(t.begin(), t.end(), indices + 3 * p);
    }
    rtcCommitGeometry(geometry.get());
    errors.throw_if_failed("rtcCommitGeometry");
    return geometry;
}

EmbreeScene::EmbreeScene(const RadiosityMesh& mesh) : impl_(std::make_unique<Impl>()), mesh_(mesh) {
    check_mesh(mesh);
    impl_->build(mesh);
}

EmbreeScene::~EmbreeScene() = default;

namespace {

/// The ray of an RTCRay or RTCRayHit (whose hit it marks empty).
RTCRay& ray_of(RTCRay& ray) {
    return ray;
}
/// Whether Embree marked the ray occluded (it sets tfar to −∞).
bool blocked(const RTCRay& ray) {
    return ray.tfar == -std::numeric_limits<float>::infinity();
}

RTCRay& ray_of(RTCRayHit& rayhit) {
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
    return rayhit.ray;
}

} // namespace

// Traces \p segments in batches of up to 256 Rays (RTCRay or RTCRayHit) through
// trace(context, rays, count), Embree's \p call, then read(index of the segment, its ray).
// \p prepare(context, first segment of the batch) readies the batch's context.
template <typename Ray, typename Trace, typename Read, typename Prepare>
void EmbreeScene::trace_batches(const char* what, const char* call,
                                std::span<const Segment> segments, std::size_t results,
                                RTCIntersectContext* context, Trace&& trace, Read&& read,
                                Prepare&& prepare) const {
    if (segments.size() != results)
        throw InternalError(fmt::format("EmbreeScene::{}: {} segments but {} results", what,
                                        segments.size(), results));
    std::array<Ray, k_ray_batch> rays;
    for (std::size_t begin = 0; begin < segments.size(); begin += k_ray_batch) {
        const std::size_t count = std::min(k_ray_batch, segments.size() - begin);
        for (std::size_t i = 0; i < count; ++i) {
            const Segment& s = segments[begin + i];
            RTCRay& ray = ray_of(rays[i]);
            ray = make_ray(s.origin, s.direction, s.tnear, s.tfar);
            ray.id = unsigned(i);
        }
        rtcInitIntersectContext(context);
        prepare(begin);
        trace(context, rays.data(), unsigned(count));
        for (std::size_t i = 0; i < count; ++i)
            read(begin + i, rays[i]);
    }
    impl_->rays.add(segments.size());
    impl_->errors.throw_if_failed(call);
}

void EmbreeScene::occluded(std::span<const Segment> segments, std::span<std::uint8_t> out) const {
    RTCIntersectContext context;
    trace_batches<RTCRay>(
        "occluded", "rtcOccluded1M", segments, out.size(), &context,
        [&](RTCIntersectContext* context, RTCRay* rays, unsigned count) {
            rtcOccluded1M(impl_->scene.get(), context, rays, count, sizeof(RTCRay));
        },
        [&](std::size_t k, const RTCRay& ray) { out[k] = blocked(ray) ? 1 : 0; },
        [](std::size_t) {});
}

void EmbreeScene::transmittance(std::span<const Segment> segments, std::span<float> out) const {
    if (!impl_->glazed_scene.get()) {
        VisibilityQuery::transmittance(segments, out);
        return;
    }
    std::array<PaneCrossings, k_ray_batch> crossings;
    PaneContext context;
    context.mesh = &mesh_;
    context.panes = &impl_->panes;
    context.crossings = crossings.data();
    std::size_t first = 0;
    trace_batches<RTCRay>(
        "transmittance", "rtcOccluded1M", segments, out.size(), &context.base,
        [&](RTCIntersectContext* c, RTCRay* rays, unsigned count) {
            rtcOccluded1M(impl_->glazed_scene.get(), c, rays, count, sizeof(RTCRay));
        },
        [&](std::size_t k, const RTCRay& ray) {
            out[k] = blocked(ray) ? 0.0f : crossings[k - first].transmittance;
        },
        [&](std::size_t begin) {
            first = begin;
            crossings.fill(PaneCrossings{});
        });
}

void EmbreeScene::first_hit(std::span<const Segment> segments, std::span<std::int32_t> hit) const {
    RTCIntersectContext context;
    trace_batches<RTCRayHit>(
        "first_hit", "rtcIntersect1M", segments, hit.size(), &context,
        [&](RTCIntersectContext* context, RTCRayHit* rays, unsigned count) {
            rtcIntersect1M(impl_->scene.get(), context, rays, count, sizeof(RTCRayHit));
        },
        [&](std::size_t k, const RTCRayHit& ray) {
            hit[k] = ray.hit.geomID == RTC_INVALID_GEOMETRY_ID
                         ? -1
                         : std::int32_t(impl_->opaque[ray.hit.primID]);
        },
        [](std::size_t) {});
}

std::uint64_t EmbreeScene::rays_traced() const {
    return impl_->rays.total();
}

EmbreeScene::Hit EmbreeScene::intersect(const Vec3f& origin, const Vec3f& direction, float tnear,
                                        float tfar) const {
    RTCRayHit rayhit{};
    rayhit.ray = make_ray(origin, direction, tnear, tfar);
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(impl_->scene.get(), &context, &rayhit);
    impl_->rays.add(1);

    Hit hit;
    if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return hit;
    hit.t = rayhit.ray.tfar;
    const std::uint32_t front = impl_->opaque[rayhit.hit.primID];
    hit.front_element = std::int32_t(front);
    if (dot(Vec3(direction), mesh_.patch_of(front).normal) < 0) {
        hit.element = std::int32_t(front);
        hit.u = rayhit.hit.u;
        hit.v = rayhit.hit.v;
        return hit;
    }
    const std::int32_t twin = mesh_.element_twin[front];
    if (twin < 0) {
        hit.back_of_one_sided = true;
        return hit;
    }
    // The twin has its own vertices in the opposite winding: locate the hit point (taken on
    // the front triangle, so it lies in the plane) in the twin's own vertex order.
    const auto& f = mesh_.triangles[front];
    const double u = rayhit.hit.u, v = rayhit.hit.v;
    const Vec3 p =
        mesh_.vertex(f[0]) * (1.0 - u - v) + mesh_.vertex(f[1]) * u + mesh_.vertex(f[2]) * v;
    const auto& b = mesh_.triangles[std::uint32_t(twin)];
    std::tie(hit.u, hit.v) =
        barycentrics(p, mesh_.vertex(b[0]), mesh_.vertex(b[1]), mesh_.vertex(b[2]));
    hit.element = twin;
    return hit;
}

float segment_transmittance(const EmbreeScene& rt, const Segment& segment, bool glazing) {
    if (!glazing) {
        std::uint8_t blocked = 0;
        rt.occluded(std::span(&segment, 1), std::span(&blocked, 1));
        return blocked ? 0.0f : 1.0f;
    }
    float t = 0;
    rt.transmittance(std::span(&segment, 1), std::span(&t, 1));
    return t;
}

} // namespace penumbra::raytrace
