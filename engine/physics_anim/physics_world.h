#pragma once
// The rigid-body simulation: fixed steps from an accumulator, interpolated rendering poses.
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "engine/core/scratch_vector.h"
#include "engine/ecs/registry.h"
#include "engine/ecs/scheduler.h"
#include "engine/physics_anim/broad_phase.h"
#include "engine/physics_anim/contact_cache.h"
#include "engine/physics_anim/contact_solver.h"
#include "engine/physics_anim/gpu_contact_solver.h"
#include "engine/physics_anim/narrow_phase.h"
#include "engine/physics_anim/sim_body.h"

namespace rtrt::physics {

struct PhysicsSettings {
    vec3 gravity{0.0f, -9.81f, 0.0f};
    float fixedStep = 1.0f / 120.0f;  // seconds
    // A frame longer than this many steps runs in slow motion rather than piling up steps.
    int maxStepsPerFrame = 8;
    int velocityIterations = 10;
    int positionIterations = 4;

    // Speeds are clamped to these after gravity each step. Contacts are speculative: a pair gets
    // contacts as soon as the gap between its shapes is under what their relative speed covers in
    // one step, and the solver lets the gap close but not go negative, so a body at up to this
    // speed stops at a plane or a box face however thin the collider (tested: a 2 cm ball at
    // 200 m/s into a plane and into a 1 cm thick box). The limit bounds how far the broad phase
    // must look ahead: 200 m/s is 1.67 m a step at 1/120 s. The price of speculative contacts is
    // an occasional early stop ("ghost" contact) of a fast body that would just have missed.
    float maxLinearSpeed = 200.0f;   // m/s
    float maxAngularSpeed = 100.0f;  // rad/s
    float contactMargin = 0.01f;     // m: contacts are kept this far ahead even at rest

    float restitutionThreshold = 0.5f;  // m/s: slower impacts do not bounce
    float linearSlop = 0.001f;          // m of overlap left uncorrected, so contacts persist
    // A contact within this distance (in the first body's frame) of one from the last step starts
    // from that contact's impulses.
    float warmStartDistance = 0.02f;  // m
    float positionCorrection = 0.2f;  // fraction of the overlap removed per step
    float linearDamping = 0.0f;       // 1/s
    float angularDamping = 0.0f;      // 1/s

    // A body slower than both speeds for timeToSleep seconds sleeps: it stops moving and costs
    // only its broad-phase box until a moving body touches it or it is given a velocity.
    float sleepLinearSpeed = 0.05f;   // m/s
    float sleepAngularSpeed = 0.05f;  // rad/s
    float timeToSleep = 0.5f;         // s

    // A world of fewer bodies steps on one thread, whatever TBB lends: the threads' start and
    // joins would cost more than they share (bench/results/physics-step-serial-vm-2026-12-05.txt).
    // The bits are the same on any number of threads, so this changes only the time.
    uint32_t minParallelBodies = 1024;
};

// Where the last Advance or Step call spent its time, summed over its steps.
struct PhysicsTimes {
    double broadPhaseMs = 0.0;   // boxes, pairs, waking, gravity, the solver's view of the bodies
    double narrowPhaseMs = 0.0;  // contacts, colouring and layout
    double solverMs = 0.0;       // warm start, velocity and position iterations, impulse cache
    double integrateMs = 0.0;    // positions and sleep
    // Of solverMs, with the GPU solver (SolveContactsOnGpu): the device's transfers and passes.
    double gpuTransferMs = 0.0;
    double gpuSolveMs = 0.0;
};

struct PhysicsStats {
    uint64_t frames = 0;      // Advance calls that found rigid bodies
    uint64_t steps = 0;       // fixed steps taken
    uint64_t bodySteps = 0;   // sum over steps of the bodies simulated
    uint32_t lastBodies = 0;  // in the last step
    uint32_t lastAwake = 0;
    uint32_t lastPairs = 0;  // broad-phase pairs
    uint32_t lastContacts = 0;
    uint32_t lastColors = 0;   // contact colours (ContactColoring), the overflow included
    uint32_t lastThreads = 0;  // that the last frame's steps could use (1 for a small world)
    PhysicsTimes lastTimes;
};

// Simulates the entities that have a RigidBody and a LocalTransform (rigid_body.h), over the
// RigidBody pool only: a registry without rigid bodies costs one pool-size check per frame.
//
// A step: sort-and-sweep broad phase in strips over speed-expanded boxes; waking; gravity; contacts
// (speculative, narrow_phase.h); warm-started sequential impulses (contact_solver.h) with
// friction, rolling resistance, restitution and split-impulse correction; symplectic Euler
// positions; sleeping. Gyroscopic torque is ignored (a tumbling box keeps its angular velocity).
// Parallel on TBB: per-body passes, the sweep and the narrow phase split their arrays; the solver
// runs the manifolds of one colour (contact_coloring.h) at once, each thread on the same region
// (a run of solver bodies laid out in sweep order) in every colour. A world of few bodies steps on
// one thread.
// Deterministic whatever the number of threads: bodies are visited in pool order, pairs in strip
// and sweep order with index tie-breaks, the colours are assigned serially in that order, and
// parallel passes write disjoint data, so the same registry contents and calls give bit-identical
// results on one build and machine, on 1 thread or 16. The contacts may be solved on the GPU
// instead (SolveContactsOnGpu): the same values (gpu_contact_solver.h).
class PhysicsWorld {
    using Entity = ecs::Entity;

  public:
    explicit PhysicsWorld(PhysicsSettings settings = {});

    // Adds frameDt to the accumulator, takes the whole fixed steps it holds (at most
    // maxStepsPerFrame; the excess time is dropped), then writes each moving body's
    // LocalTransform, interpolated between its last two states by the remaining fraction of a
    // step (Fiedler 2004, "Fix Your Timestep!"), and marks it changed.
    void Advance(ecs::Registry& registry, float frameDt);
    // Takes exactly `steps` fixed steps and writes the final poses without interpolation; the
    // accumulator is left alone. For tests and tools.
    void Step(ecs::Registry& registry, int steps = 1);

    // Kinetic (linear and rotational) plus gravitational potential energy of the dynamic bodies,
    // in joules, with potential 0 at the origin.
    double MechanicalEnergy(const ecs::Registry& registry) const;

    // A body's motion flags (motion_).
    static constexpr uint8_t kDynamic = 1;
    static constexpr uint8_t kAwake = 2;
    static constexpr uint8_t kResting = 4;  // restingTime > 0
    static constexpr uint8_t kFresh = 8;    // a static body just placed or moved (SimBody::fresh)

    // Solves the contacts on the first CUDA device from the next step on (the rest of the step
    // stays on the CPU). Throws std::runtime_error saying why when there is none.
    void SolveContactsOnGpu();
    bool SolvesContactsOnGpu() const { return gpuSolver_ != nullptr; }

    // Frames of FRAME_DT each, as an offline player advances (play --fps): every frame takes all
    // the steps its time holds, where the real-time cap (maxStepsPerFrame) ran frames longer
    // than 8 steps in slow motion (at 5 fps physics ran at a third of its speed).
    void KeepUpWithFrames(float frameDt) {
        const int steps = static_cast<int>(std::ceil(double(frameDt) / settings_.fixedStep)) + 1;
        settings_.maxStepsPerFrame = std::max(settings_.maxStepsPerFrame, steps);
    }
    const PhysicsSettings& Settings() const { return settings_; }
    const PhysicsStats& Stats() const { return stats_; }
    // Where between the last two steps the rendered poses are, in [0, 1).
    float InterpolationAlpha() const {
        return static_cast<float>(accumulator_ / settings_.fixedStep);
    }

  private:
    // stepFollows: a step follows (StartStep is done for it while the bodies are filled).
    void Gather(ecs::Registry& registry, bool stepFollows);
    // A body's state at the start of a step: its motion flags, the pose and velocities the step
    // starts from, its rotation matrix and world inverse inertia. Per body, so that it rides in
    // the loop over the bodies before the step (the gathering, or the last step's positions).
    void StartStep(size_t body);
    // anotherFollows: the frame takes another step after this one.
    void TakeStep(bool anotherFollows);
    void FindPairs();
    void WakeTouched();
    // Gravity and damping, and each body's solver view (GatherSolverBody) for the contact passes.
    void IntegrateVelocities();
    void FindContacts();
    // A pair's or a plane and body's manifold (its bodies in candidateBodies_); no contact when
    // manifold.count is 0. rolling: the contacts' rolling limit (RollingLimit).
    struct Candidate {
        float rolling;  // first: with the normal and the first points in one cache line
        Manifold manifold;
    };
    // The rolling resistance of a contact between first and second, as the largest rolling
    // impulse per unit normal impulse: lever is the radius of the sphere that can roll on it (0
    // when none can).
    float RollingLimit(uint32_t first, uint32_t second, float lever) const;
    void CollideCandidates();
    void LayOutContacts();
    // The contacts of a candidate whose manifold goes from body first to body second.
    void WriteContacts(const Candidate& candidate, uint32_t first, uint32_t second,
                       Contact* out) const;
    // Each contact starts from the impulses of last step's nearby contact of the pair, if any.
    void SeedFromLastStep();
    void RememberImpulses();
    // Positions from the solved velocities, then sleep (a body slow for timeToSleep stops); then
    // StartStep when another step follows.
    void IntegratePositions(bool anotherFollows);
    void WriteBack(ecs::Registry& registry, float alpha);
    float Margin(const SimBody& body) const;

    PhysicsSettings settings_;
    SolverSettings solver_;
    double accumulator_ = 0.0;
    PhysicsStats stats_;

    std::vector<SimBody> bodies_;
    struct BodyComponents {
        Entity entity;
        RigidBody* body;
        LocalTransform* local;
    };
    std::vector<BodyComponents> components_;  // Gather's: each body's, in view order
    // Per body, kDynamic | kAwake | kResting as the step's serial passes need them (WakeTouched,
    // the colouring): 1 byte each instead of a cache miss on the body.
    std::vector<uint8_t> motion_;
    std::vector<uint32_t> planes_;            // bodies with a plane collider
    std::vector<uint8_t> moved_;              // WriteBack's: the body's transform changed
    std::vector<ecs::Entity> movedEntities_;  // and those bodies' entities, in body order
    std::vector<uint8_t> places_;             // Gather's: each body's list (broad phase or not)
    std::vector<uint32_t> broadBodies_;       // body of each broad-phase box (Gather's)
    std::vector<uint32_t> outsideBodies_;     // the others: planes, bodies without a collider
    std::vector<BroadPhaseBox> boxes_;
    std::vector<std::pair<uint32_t, uint32_t>> pairs_;  // body indices
    std::vector<Candidate> candidates_;                 // the pairs, then a row of bodies per plane
    std::vector<uint8_t> candidatePoints_;              // each candidate's manifold.count
    // Each candidate's bodies, the manifold's first and second, where it has points: apart from
    // the manifolds, so that LayOutContacts reads 8 bytes per hit instead of a cache line.
    struct CandidateBodies {
        uint32_t first;
        uint32_t second;
    };
    ScratchVector<CandidateBodies> candidateBodies_;
    struct Hit {
        uint32_t candidate;   // that has contacts
        uint32_t slot;        // colour * regions + region (LayOutContacts)
        uint32_t manifold;    // its place in batches_
        uint32_t firstPoint;  // its first contact's place in contacts_
        uint32_t first;       // the candidate's bodies and points, for the serial passes
        uint32_t second;
        uint8_t points;
        bool firstMoves;
        bool secondMoves;
    };
    ScratchVector<Hit> hits_;  // sized to the candidates, then compacted: no zeros written
    std::vector<uint32_t> slotManifolds_;
    std::vector<uint32_t> slotPoints_;
    std::vector<uint32_t> solverSlots_;  // each body's place among the solver bodies
    ContactColoring coloring_;
    std::vector<Contact> contacts_;  // colour by colour, as batches_ says
    ContactBatches batches_;
    std::vector<SolverBody> solverBodies_;
    std::vector<BodyAtStart> bodyStarts_;
    std::vector<PseudoVelocity> pseudoVelocities_;
    ContactSolverScratch solverScratch_;
    std::unique_ptr<GpuContactSolver> gpuSolver_;
    // Runs work on one thread when the world has fewer than minParallelBodies bodies.
    template <typename Work>
    void OnThreadsFor(size_t bodies, const Work& work);
    std::unique_ptr<tbb::task_arena> oneThread_;

    ContactCache cache_;  // last step's touching contacts, for warm starting
    ContactCache nextCache_;
    std::vector<uint32_t> chunkStarts_;     // ParallelCompact's scratch
    ScratchVector<uint32_t> sleeperPairs_;  // pairs_ holding a sleeper (WakeTouched)
    SweepAndPrune sweep_;
    // The loops over bodies_ (and over the broad-phase boxes) run each chunk of bodies on the
    // same thread from loop to loop, so that a body's cache lines stay with one core.
    tbb::affinity_partitioner bodyAffinity_;
    tbb::affinity_partitioner boxAffinity_;
};

// Adds world.Advance to phase "simulation" under the name "physics".
void AddPhysicsSystem(ecs::Scheduler& scheduler, PhysicsWorld& world);

}  // namespace rtrt::physics
