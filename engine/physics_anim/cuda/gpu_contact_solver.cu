// Compiled with -fmad=false, IEEE division and square roots and no flush to zero
// (CMakeLists.txt): every product and sum is rounded on its own, as on the CPU
// (-ffp-contract=off), so the passes give the CPU rows' results.
#include <cooperative_groups.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>

#include "engine/core/cuda_check.h"
#include "engine/core/cuda_device_guard.h"
#include "engine/core/cuda_unavailable.h"
#include "engine/core/device_buffer.h"
#include "engine/core/parallel_for.h"
#include "engine/physics_anim/contact_rows.h"
#include "engine/physics_anim/contact_setup.h"
#include "engine/physics_anim/gpu_contact_solver.h"

namespace rtrt::physics {

namespace {

namespace cg = cooperative_groups;

// The passes' kernel holds a point and the next one in registers (158 a thread): 512-thread
// blocks do not fit on an SM.
constexpr int kThreads = 256;
constexpr uint32_t kMaxColors = ContactColoring::kColors + 1;  // and the overflow

// One contact point as the passes read it: 128 bytes, fetched in 16-byte loads.
struct alignas(16) PointSetUp {
    vec3 normal;
    ContactSetUp setUp;
};
static_assert(sizeof(PointSetUp) == 128);

// What the passes change of a contact point.
struct alignas(16) PointState {
    float normalImpulse;
    float tangentImpulse1;
    float tangentImpulse2;
    float pseudoImpulse;
    vec3 rollingImpulse;
};

struct Impulses {
    float normal;
    float tangent1;
    float tangent2;
};

// The records the host fills and the device reads, byte for byte.
static_assert(sizeof(Contact) == 52 && sizeof(BodyAtStart) == 48);
static_assert(sizeof(SolverBody) == 64 && sizeof(PseudoVelocity) == 32);
static_assert(sizeof(PointState) == 32 && sizeof(Impulses) == 12);

struct PassCounts {
    int velocityAndPosition;  // the position iterations that ride along the first velocity ones
    int velocity;             // velocity iterations after them
    int position;             // position iterations after restitution
};

struct SolveArgs {
    SolverBody* bodies;
    PseudoVelocity* pseudo;
    const PointSetUp* setUps;
    PointState* states;
    const uint32_t* manifoldBegin;
    const uint2* manifoldSlots;  // the two bodies of each manifold
    uint32_t colorBegin[kMaxColors + 1];
    uint32_t colors;
    bool lastIsOverflow;
    float positionRate;
    PassCounts passes;
};

// A body's velocities while a thread solves one manifold's contacts.
struct BodyState {
    vec3 velocity;
    vec3 angularVelocity;
    float invMass;
    glm::mat3 invInertia;
};

__device__ BodyState Load(const SolverBody& s) {
    return {s.velocity, s.angularVelocity, s.invMass, s.invInertia};
}

__device__ vec3 RelativeVelocity(const BodyState& a, const BodyState& b, const ContactSetUp& s) {
    return b.velocity + glm::cross(b.angularVelocity, s.anchorB) - a.velocity -
           glm::cross(a.angularVelocity, s.anchorA);
}

// b gains the impulse at the contact point, a loses it (contact_rows.cpp's Push).
__device__ void Push(BodyState& a, BodyState& b, const ContactSetUp& s, vec3 impulse) {
    a.velocity = a.velocity - a.invMass * impulse;
    a.angularVelocity = a.angularVelocity - a.invInertia * glm::cross(s.anchorA, impulse);
    b.velocity = b.velocity + b.invMass * impulse;
    b.angularVelocity = b.angularVelocity + b.invInertia * glm::cross(s.anchorB, impulse);
}

// lanes.h's Max, not fmaxf: the same result when an operand is NaN.
__device__ float Max(float a, float b) { return a > b ? a : b; }

__device__ void WarmStart(BodyState& a, BodyState& b, const PointSetUp& p, const PointState& q) {
    Push(a, b, p.setUp,
         q.normalImpulse * p.normal + q.tangentImpulse1 * p.setUp.tangent1 +
             q.tangentImpulse2 * p.setUp.tangent2);
}

__device__ void SolveVelocity(BodyState& a, BodyState& b, const PointSetUp& p, PointState& q) {
    const ContactSetUp& s = p.setUp;
    if (s.rollingLimit > 0.0f && q.normalImpulse > 0.0f) {
        const vec3 spin = b.angularVelocity - a.angularVelocity;
        vec3 impulse = q.rollingImpulse - s.rollingMass * spin;
        const float maxRolling = s.rollingLimit * q.normalImpulse;
        const float length = sqrtf(glm::dot(impulse, impulse));
        impulse = (length > maxRolling ? maxRolling / length : 1.0f) * impulse;
        const vec3 delta = impulse - q.rollingImpulse;
        q.rollingImpulse = impulse;
        a.angularVelocity = a.angularVelocity - a.invInertia * delta;
        b.angularVelocity = b.angularVelocity + b.invInertia * delta;
    }
    const float maxFriction = s.friction * q.normalImpulse;
    if (maxFriction > 0.0f) {
        const vec3 dv = RelativeVelocity(a, b, s);
        float t1 = q.tangentImpulse1 - s.tangentMass1 * glm::dot(s.tangent1, dv);
        float t2 = q.tangentImpulse2 - s.tangentMass2 * glm::dot(s.tangent2, dv);
        const float length = sqrtf(t1 * t1 + t2 * t2);
        const float clamp = length > maxFriction ? maxFriction / length : 1.0f;
        t1 = t1 * clamp;
        t2 = t2 * clamp;
        const float d1 = t1 - q.tangentImpulse1;
        const float d2 = t2 - q.tangentImpulse2;
        Push(a, b, s, d1 * s.tangent1 + d2 * s.tangent2);
        q.tangentImpulse1 = t1;
        q.tangentImpulse2 = t2;
    }
    const float vn = glm::dot(p.normal, RelativeVelocity(a, b, s));
    const float impulse = Max(q.normalImpulse - s.normalMass * (vn + s.allowedApproach), 0.0f);
    Push(a, b, s, (impulse - q.normalImpulse) * p.normal);
    q.normalImpulse = impulse;
}

__device__ void Restitute(BodyState& a, BodyState& b, const PointSetUp& p, PointState& q) {
    const ContactSetUp& s = p.setUp;
    if (!(s.bounce > 0.0f && q.normalImpulse > 0.0f)) return;
    const float vn = glm::dot(p.normal, RelativeVelocity(a, b, s));
    const float impulse = Max(q.normalImpulse - s.normalMass * (vn - s.bounce), 0.0f);
    Push(a, b, s, (impulse - q.normalImpulse) * p.normal);
    q.normalImpulse = impulse;
}

__device__ void SolvePosition(PseudoVelocity& pa, PseudoVelocity& pb, const BodyState& a,
                              const BodyState& b, const PointSetUp& p, PointState& q, float rate) {
    const ContactSetUp& s = p.setUp;
    if (!(s.overlap > 0.0f)) return;
    const float vn = glm::dot(p.normal, pb.linear + glm::cross(pb.angular, s.anchorB) - pa.linear -
                                            glm::cross(pa.angular, s.anchorA));
    const float impulse = Max(q.pseudoImpulse - s.normalMass * (vn - rate * s.overlap), 0.0f);
    const vec3 push = (impulse - q.pseudoImpulse) * p.normal;
    q.pseudoImpulse = impulse;
    pa.linear = pa.linear - a.invMass * push;
    pa.angular = pa.angular - a.invInertia * glm::cross(s.anchorA, push);
    pb.linear = pb.linear + b.invMass * push;
    pb.angular = pb.angular + b.invInertia * glm::cross(s.anchorB, push);
}

// One pass over manifold m's contacts, in order, on its two bodies. A body that does not move
// (zero inverse mass) is only read: other threads may read it at the same time. The next
// point's loads are issued before this point's arithmetic, which is one long dependent chain.
__device__ void SolveManifold(const SolveArgs& args, uint32_t m, RowPass pass) {
    const uint32_t begin = args.manifoldBegin[m];
    const uint32_t end = args.manifoldBegin[m + 1];
    const uint2 slots = args.manifoldSlots[m];
    PointSetUp next = args.setUps[begin];
    PointState nextState = args.states[begin];
    BodyState a = Load(args.bodies[slots.x]);
    BodyState b = Load(args.bodies[slots.y]);
    const bool velocity = pass == RowPass::kVelocity || pass == RowPass::kVelocityAndPosition;
    const bool position = pass == RowPass::kPosition || pass == RowPass::kVelocityAndPosition;
    PseudoVelocity pa{};
    PseudoVelocity pb{};
    if (position) {
        pa = args.pseudo[slots.x];
        pb = args.pseudo[slots.y];
    }
    for (uint32_t k = begin; k < end; ++k) {
        const PointSetUp p = next;
        PointState q = nextState;
        if (k + 1 < end) {
            next = args.setUps[k + 1];
            nextState = args.states[k + 1];
        }
        if (pass == RowPass::kWarmStart) WarmStart(a, b, p, q);
        if (velocity) SolveVelocity(a, b, p, q);
        if (pass == RowPass::kRestitution) Restitute(a, b, p, q);
        if (position) SolvePosition(pa, pb, a, b, p, q, args.positionRate);
        if (pass != RowPass::kWarmStart) args.states[k] = q;
    }
    if (pass != RowPass::kPosition) {
        if (a.invMass > 0.0f) {
            args.bodies[slots.x].velocity = a.velocity;
            args.bodies[slots.x].angularVelocity = a.angularVelocity;
        }
        if (b.invMass > 0.0f) {
            args.bodies[slots.y].velocity = b.velocity;
            args.bodies[slots.y].angularVelocity = b.angularVelocity;
        }
    }
    if (position) {
        if (a.invMass > 0.0f) args.pseudo[slots.x] = pa;
        if (b.invMass > 0.0f) args.pseudo[slots.y] = pb;
    }
}

// One pass colour by colour, a grid-wide barrier after each. The overflow's manifolds may share
// bodies: one thread solves them in order.
__device__ void SolvePass(const SolveArgs& args, RowPass pass, cg::grid_group& grid) {
    const auto thread = static_cast<uint32_t>(grid.thread_rank());
    const auto threads = static_cast<uint32_t>(grid.size());
    for (uint32_t color = 0; color < args.colors; ++color) {
        const uint32_t begin = args.colorBegin[color];
        const uint32_t end = args.colorBegin[color + 1];
        if (args.lastIsOverflow && color + 1 == args.colors) {
            if (thread == 0) {
                for (uint32_t m = begin; m < end; ++m) SolveManifold(args, m, pass);
            }
        } else {
            for (uint32_t m = begin + thread; m < end; m += threads) SolveManifold(args, m, pass);
        }
        grid.sync();
    }
}

__global__ void SolveKernel(SolveArgs args) {
    cg::grid_group grid = cg::this_grid();
    SolvePass(args, RowPass::kWarmStart, grid);
    for (int i = 0; i < args.passes.velocityAndPosition; ++i) {
        SolvePass(args, RowPass::kVelocityAndPosition, grid);
    }
    for (int i = 0; i < args.passes.velocity; ++i) SolvePass(args, RowPass::kVelocity, grid);
    SolvePass(args, RowPass::kRestitution, grid);
    for (int i = 0; i < args.passes.position; ++i) SolvePass(args, RowPass::kPosition, grid);
}

// One thread per manifold: its points' set-up from the bodies at the start of the passes.
__global__ void SetUpKernel(const Contact* contacts, const uint32_t* manifoldBegin,
                            uint32_t manifolds, const uint32_t* slotOfBody,
                            const BodyAtStart* starts, const SolverBody* bodies,
                            SolverSettings settings, PointSetUp* setUps, PointState* states,
                            uint2* manifoldSlots) {
    const uint32_t m = blockIdx.x * blockDim.x + threadIdx.x;
    if (m >= manifolds) return;
    const uint32_t begin = manifoldBegin[m];
    const uint32_t end = manifoldBegin[m + 1];
    const uint32_t slotA = slotOfBody[contacts[begin].a];
    const uint32_t slotB = slotOfBody[contacts[begin].b];
    manifoldSlots[m] = make_uint2(slotA, slotB);
    for (uint32_t k = begin; k < end; ++k) {
        const Contact c = contacts[k];
        setUps[k] = {c.normal, SetUpContact(c, starts[slotA], starts[slotB], bodies[slotA],
                                            bodies[slotB], settings)};
        states[k] = {c.normalImpulse, c.tangentImpulse1, c.tangentImpulse2, 0.0f, vec3(0.0f)};
    }
}

__global__ void ImpulsesKernel(const PointState* states, uint32_t count, Impulses* out) {
    const uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
    if (k >= count) return;
    out[k] = {states[k].normalImpulse, states[k].tangentImpulse1, states[k].tangentImpulse2};
}

uint32_t BlocksFor(uint32_t count) { return (count + kThreads - 1) / kThreads; }

// A page-locked host array: copies between it and the device run at the bus's full speed.
class PinnedBytes {
  public:
    PinnedBytes() = default;
    PinnedBytes(const PinnedBytes&) = delete;
    PinnedBytes& operator=(const PinnedBytes&) = delete;
    ~PinnedBytes() {
        if (data_ != nullptr) cudaFreeHost(data_);
    }
    // At least bytes, contents not kept.
    void Reserve(size_t bytes) {
        if (bytes <= size_) return;
        if (data_ != nullptr) RT_CUDA_CHECK(cudaFreeHost(data_));
        data_ = nullptr;
        size_ = 0;
        RT_CUDA_CHECK(cudaMallocHost(&data_, bytes + bytes / 4));
        size_ = bytes + bytes / 4;
    }
    std::byte* Data() const { return static_cast<std::byte*>(data_); }

  private:
    void* data_ = nullptr;
    size_t size_ = 0;
};

// memcpy on every thread TBB lends: a step's arrays are megabytes, and one core copies them at a
// fraction of the memory's speed.
void ParallelCopy(void* to, const void* from, size_t bytes) {
    constexpr size_t kChunk = size_t{64} << 10;
    ParallelFor(0, (bytes + kChunk - 1) / kChunk, 1, [&](size_t c) {
        const size_t at = c * kChunk;
        std::memcpy(static_cast<std::byte*>(to) + at, static_cast<const std::byte*>(from) + at,
                    std::min(kChunk, bytes - at));
    });
}

// Where a step's arrays lie, alike on the host (page-locked) and on the device: what goes up is
// [0, UploadBytes()), what comes back [bodies, end) - the bodies go both ways, and the pseudo
// velocities start as zeros on the device.
struct StagingLayout {
    size_t contacts, manifoldBegin, slotOfBody, starts, bodies, pseudo, impulses, end;

    StagingLayout(size_t contactCount, size_t manifoldCount, size_t bodyCount, size_t slots) {
        size_t at = 0;
        const auto place = [&](size_t bytes) {
            const size_t where = at;
            at = (at + bytes + 255) / 256 * 256;
            return where;
        };
        contacts = place(contactCount * sizeof(Contact));
        manifoldBegin = place((manifoldCount + 1) * sizeof(uint32_t));
        slotOfBody = place(bodyCount * sizeof(uint32_t));
        starts = place(slots * sizeof(BodyAtStart));
        bodies = place(slots * sizeof(SolverBody));
        pseudo = place(slots * sizeof(PseudoVelocity));
        impulses = place(contactCount * sizeof(Impulses));
        end = at;
    }
    size_t UploadBytes() const { return pseudo; }
};

class CudaContactSolver final : public GpuContactSolver {
  public:
    CudaContactSolver(int device, int maxBlocks) : device_(device), maxBlocks_(maxBlocks) {
        CudaDeviceGuard guard(device_);
        // The highest priority: in pipelined play the step runs while the last frame traces on
        // the same GPU, and the step's passes, one short stage after another, would otherwise
        // queue behind the trace's blocks; the CPU waits for them.
        int lowest = 0, highest = 0;
        RT_CUDA_CHECK(cudaDeviceGetStreamPriorityRange(&lowest, &highest));
        RT_CUDA_CHECK(cudaStreamCreateWithPriority(&stream_, cudaStreamNonBlocking, highest));
        for (cudaEvent_t& e : events_) RT_CUDA_CHECK(cudaEventCreate(&e));
    }
    ~CudaContactSolver() override {
        for (cudaEvent_t e : events_) {
            if (e != nullptr) cudaEventDestroy(e);
        }
        if (stream_ != nullptr) cudaStreamDestroy(stream_);
    }
    CudaContactSolver(const CudaContactSolver&) = delete;
    CudaContactSolver& operator=(const CudaContactSolver&) = delete;

    void Solve(std::span<const uint32_t> slotOfBody, std::span<const BodyAtStart> starts,
               std::span<SolverBody> solverBodies, std::span<PseudoVelocity> pseudo,
               std::span<Contact> contacts, const ContactBatches& batches,
               const SolverSettings& settings) override {
        times_ = {};
        const uint32_t colors = batches.Colors();
        if (colors == 0 || contacts.empty()) return;
        if (colors > kMaxColors) throw std::runtime_error("GPU contact solver: too many colours");
        CudaDeviceGuard guard(device_);
        const auto count = static_cast<uint32_t>(contacts.size());
        const size_t slots = solverBodies.size();
        const StagingLayout layout(count, batches.Manifolds(), slotOfBody.size(), slots);
        host_.Reserve(layout.end);
        if (deviceArena_.Size() < layout.end) deviceArena_.Resize(layout.end + layout.end / 4);
        if (setUps_.Size() < count) setUps_.Resize(count + count / 4);
        if (states_.Size() < count) states_.Resize(count + count / 4);
        const uint32_t manifolds = batches.Manifolds();
        if (manifoldSlots_.Size() < manifolds) manifoldSlots_.Resize(manifolds + manifolds / 4);
        std::byte* const host = host_.Data();
        std::byte* const dev = deviceArena_.Data();
        ParallelCopy(host + layout.contacts, contacts.data(), contacts.size_bytes());
        ParallelCopy(host + layout.manifoldBegin, batches.manifoldBegin.data(),
                     batches.manifoldBegin.size() * sizeof(uint32_t));
        ParallelCopy(host + layout.slotOfBody, slotOfBody.data(), slotOfBody.size_bytes());
        ParallelCopy(host + layout.starts, starts.data(), starts.size_bytes());
        ParallelCopy(host + layout.bodies, solverBodies.data(), solverBodies.size_bytes());

        const auto at = [&](size_t offset) { return dev + offset; };
        RT_CUDA_CHECK(cudaEventRecord(events_[0], stream_));
        RT_CUDA_CHECK(
            cudaMemcpyAsync(dev, host, layout.UploadBytes(), cudaMemcpyHostToDevice, stream_));
        RT_CUDA_CHECK(
            cudaMemsetAsync(at(layout.pseudo), 0, slots * sizeof(PseudoVelocity), stream_));
        RT_CUDA_CHECK(cudaEventRecord(events_[1], stream_));
        auto* const bodies = reinterpret_cast<SolverBody*>(at(layout.bodies));
        const auto* manifoldBegin = reinterpret_cast<const uint32_t*>(at(layout.manifoldBegin));
        SetUpKernel<<<BlocksFor(manifolds), kThreads, 0, stream_>>>(
            reinterpret_cast<const Contact*>(at(layout.contacts)), manifoldBegin, manifolds,
            reinterpret_cast<const uint32_t*>(at(layout.slotOfBody)),
            reinterpret_cast<const BodyAtStart*>(at(layout.starts)), bodies, settings,
            setUps_.Data(), states_.Data(), manifoldSlots_.Data());
        RT_CUDA_CHECK_LAUNCH();

        SolveArgs args{};
        args.bodies = bodies;
        args.pseudo = reinterpret_cast<PseudoVelocity*>(at(layout.pseudo));
        args.setUps = setUps_.Data();
        args.states = states_.Data();
        args.manifoldBegin = manifoldBegin;
        args.manifoldSlots = manifoldSlots_.Data();
        uint32_t widest = 1;
        for (uint32_t c = 0; c <= colors; ++c) args.colorBegin[c] = batches.colorBegin[c];
        for (uint32_t c = 0; c < colors; ++c) {
            widest = std::max(widest, batches.colorBegin[c + 1] - batches.colorBegin[c]);
        }
        args.colors = colors;
        args.lastIsOverflow = batches.lastIsOverflow;
        args.positionRate = settings.positionCorrection / settings.dt;
        const int shared = std::min(settings.velocityIterations, settings.positionIterations);
        args.passes = {shared, settings.velocityIterations - shared,
                       settings.positionIterations - shared};
        const auto blocks = static_cast<int>(
            std::min<uint32_t>(BlocksFor(widest), static_cast<uint32_t>(maxBlocks_)));
        void* params[] = {&args};
        RT_CUDA_CHECK(cudaLaunchCooperativeKernel(reinterpret_cast<const void*>(&SolveKernel),
                                                  dim3(blocks), dim3(kThreads), params, 0,
                                                  stream_));
        ImpulsesKernel<<<BlocksFor(count), kThreads, 0, stream_>>>(
            states_.Data(), count, reinterpret_cast<Impulses*>(at(layout.impulses)));
        RT_CUDA_CHECK_LAUNCH();
        RT_CUDA_CHECK(cudaEventRecord(events_[2], stream_));
        RT_CUDA_CHECK(cudaMemcpyAsync(host + layout.bodies, at(layout.bodies),
                                      layout.end - layout.bodies, cudaMemcpyDeviceToHost, stream_));
        RT_CUDA_CHECK(cudaEventRecord(events_[3], stream_));
        RT_CUDA_CHECK(cudaStreamSynchronize(stream_));

        ParallelCopy(solverBodies.data(), host + layout.bodies, solverBodies.size_bytes());
        ParallelCopy(pseudo.data(), host + layout.pseudo, pseudo.size_bytes());
        const auto* impulses = reinterpret_cast<const Impulses*>(host + layout.impulses);
        ParallelFor(0, count, 4096, [&](size_t k) {
            contacts[k].normalImpulse = impulses[k].normal;
            contacts[k].tangentImpulse1 = impulses[k].tangent1;
            contacts[k].tangentImpulse2 = impulses[k].tangent2;
        });
        float ms[3] = {};
        for (int i = 0; i < 3; ++i) {
            RT_CUDA_CHECK(cudaEventElapsedTime(&ms[i], events_[i], events_[i + 1]));
        }
        times_ = {ms[0], ms[1], ms[2]};
    }

    GpuSolverTimes LastTimes() const override { return times_; }

  private:
    int device_;
    int maxBlocks_;
    cudaStream_t stream_ = nullptr;
    cudaEvent_t events_[4] = {};
    PinnedBytes host_;
    DeviceBuffer<std::byte> deviceArena_;
    DeviceBuffer<PointSetUp> setUps_;
    DeviceBuffer<PointState> states_;
    DeviceBuffer<uint2> manifoldSlots_;
    GpuSolverTimes times_;
};

}  // namespace

namespace {

// Create's work; CUDA failures throw (RT_CUDA_CHECK) and Create turns them into its reason.
std::unique_ptr<GpuContactSolver> CreateOnDevice0(std::string* why) {
    int devices = 0;
    const cudaError_t counted = cudaGetDeviceCount(&devices);
    if (counted != cudaSuccess || devices == 0) {
        cudaGetLastError();  // clear the sticky error
        if (why) {
            *why = "no usable CUDA device (" + NoCudaDeviceReason(counted) + ")";
        }
        return nullptr;
    }
    constexpr int kDevice = 0;
    int cooperative = 0;
    RT_CUDA_CHECK(cudaDeviceGetAttribute(&cooperative, cudaDevAttrCooperativeLaunch, kDevice));
    if (cooperative == 0) {
        if (why) *why = "CUDA device 0 has no cooperative launches";
        return nullptr;
    }
    CudaDeviceGuard guard(kDevice);
    int perSm = 0;
    int sms = 0;
    RT_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(
        &perSm, reinterpret_cast<const void*>(&SolveKernel), kThreads, 0));
    RT_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, kDevice));
    if (perSm == 0) {
        if (why) *why = "the solver's kernel does not fit on an SM of CUDA device 0";
        return nullptr;
    }
    return std::make_unique<CudaContactSolver>(kDevice, perSm * sms);
}

}  // namespace

std::unique_ptr<GpuContactSolver> GpuContactSolver::Create(std::string* why) {
    try {
        return CreateOnDevice0(why);
    } catch (const std::runtime_error& e) {  // e.g. a build without code for this GPU
        cudaGetLastError();
        if (why) *why = e.what();
        return nullptr;
    }
}

}  // namespace rtrt::physics
