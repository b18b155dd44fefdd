#include "engine/physics_anim/physics_world.h"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/core/parallel_compact.h"
#include "engine/core/parallel_for.h"
#include "engine/core/timer.h"
#include "engine/physics_anim/narrow_phase.h"
#include "engine/physics_anim/stage_runner.h"

namespace rtrt::physics {

using ecs::Entity;
using ecs::Registry;

namespace {

OrientedBox BoxOf(const SimBody& body) {
    return {body.position, body.rotation, body.collider.halfExtents};
}

// Work per TBB task: each element is a few dozen to a few hundred flops.
constexpr size_t kBodyGrain = 1024;
constexpr size_t kPairGrain = 128;

uint8_t MotionOf(const SimBody& s) {
    return static_cast<uint8_t>(
        (s.dynamic ? PhysicsWorld::kDynamic : 0) | (s.awake ? PhysicsWorld::kAwake : 0) |
        (s.restingTime > 0.0f ? PhysicsWorld::kResting : 0) | (s.fresh ? PhysicsWorld::kFresh : 0));
}

void ClampLength(vec3& v, float maxLength) {
    const float length2 = glm::dot(v, v);
    if (length2 > maxLength * maxLength) v *= maxLength / std::sqrt(length2);
}

// Starts loading what the passes over contacts read of a contact's first body, which they meet
// in no order: its handle, position and rotation (a SimBody's first two or three cache lines).
void PrefetchPose(const SimBody& s) {
    _mm_prefetch(reinterpret_cast<const char*>(&s.entity), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(&s.position), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(&s.rotation + 1) - 1, _MM_HINT_T0);
}

}  // namespace

PhysicsWorld::PhysicsWorld(PhysicsSettings settings)
    : settings_(settings),
      solver_{settings.fixedStep,
              settings.gravity,
              settings.velocityIterations,
              settings.positionIterations,
              settings.restitutionThreshold,
              settings.linearSlop,
              settings.positionCorrection} {}

void PhysicsWorld::SolveContactsOnGpu() {
    std::string why;
    gpuSolver_ = GpuContactSolver::Create(&why);
    if (!gpuSolver_) throw std::runtime_error("cannot solve contacts on the GPU: " + why);
}

void PhysicsWorld::Advance(Registry& registry, float frameDt) {
    if (registry.Count<RigidBody>() == 0) return;  // no bodies, no cost
    ++stats_.frames;
    const double step = settings_.fixedStep;
    if (frameDt > 0.0f) accumulator_ += frameDt;
    const auto due = static_cast<int>(accumulator_ / step);
    const int steps = std::min(due, settings_.maxStepsPerFrame);
    accumulator_ -= steps * step;
    if (accumulator_ >= step) accumulator_ = std::fmod(accumulator_, step);  // drop what is late

    stats_.lastTimes = {};
    OnThreadsFor(registry.Count<RigidBody>(), [&] {
        Gather(registry, steps > 0);
        for (int i = 0; i < steps; ++i) TakeStep(i + 1 < steps);
        WriteBack(registry, InterpolationAlpha());
    });
}

void PhysicsWorld::Step(Registry& registry, int steps) {
    if (registry.Count<RigidBody>() == 0) return;
    stats_.lastTimes = {};
    OnThreadsFor(registry.Count<RigidBody>(), [&] {
        Gather(registry, steps > 0);
        for (int i = 0; i < steps; ++i) TakeStep(i + 1 < steps);
        WriteBack(registry, 1.0f);
    });
}

template <typename Work>
void PhysicsWorld::OnThreadsFor(size_t bodies, const Work& work) {
    const auto counted = [&] {
        stats_.lastThreads = static_cast<uint32_t>(StageRunner::AvailableThreads());
        work();
    };
    if (bodies >= settings_.minParallelBodies) {
        counted();
        return;
    }
    if (!oneThread_) oneThread_ = std::make_unique<tbb::task_arena>(1);
    oneThread_->execute(counted);
}

void PhysicsWorld::StartStep(size_t i) {
    SimBody& s = bodies_[i];
    motion_[i] = MotionOf(s);
    // A static body just placed or moved keeps where it was through its first step (Gather).
    if (!s.fresh) {
        s.previousPosition = s.position;
        s.previousOrientation = s.orientation;
    }
    s.fresh = false;  // for its first step only
    s.rotation = glm::mat3_cast(s.orientation);
    s.startVelocity = s.velocity;
    s.startAngularVelocity = s.angularVelocity;
    s.invInertiaWorld =
        s.awake ? WorldInverseInertia(s.rotation, s.invInertiaLocal) : glm::mat3(0.0f);
}

void PhysicsWorld::TakeStep(bool anotherFollows) {
    ++stats_.steps;
    stats_.bodySteps += bodies_.size();
    stats_.lastBodies = static_cast<uint32_t>(bodies_.size());
    PhysicsTimes& times = stats_.lastTimes;
    Stopwatch clock;
    FindPairs();
    WakeTouched();
    IntegrateVelocities();
    times.broadPhaseMs += clock.Milliseconds();
    clock.Restart();
    FindContacts();
    times.narrowPhaseMs += clock.Milliseconds();
    clock.Restart();
    SeedFromLastStep();
    if (gpuSolver_) {
        gpuSolver_->Solve(solverSlots_, bodyStarts_, solverBodies_, pseudoVelocities_, contacts_,
                          batches_, solver_);
        const GpuSolverTimes gpu = gpuSolver_->LastTimes();
        times.gpuTransferMs += gpu.uploadMs + gpu.downloadMs;
        times.gpuSolveMs += gpu.solveMs;
    } else {
        SolveContacts(solverSlots_, bodyStarts_, solverBodies_, pseudoVelocities_, contacts_,
                      batches_, solver_, solverScratch_);
    }
    RememberImpulses();
    times.solverMs += clock.Milliseconds();
    clock.Restart();
    IntegratePositions(anotherFollows);
    times.integrateMs += clock.Milliseconds();
}

float PhysicsWorld::Margin(const SimBody& s) const {
    const float h = settings_.fixedStep;
    if (!s.awake) return 0.5f * settings_.contactMargin;
    // Gravity is added after the broad phase: allow for one step of it.
    const float speed = glm::length(s.velocity) + glm::length(settings_.gravity) * h;
    return 0.5f * settings_.contactMargin + (std::min(speed, settings_.maxLinearSpeed) +
                                             glm::length(s.angularVelocity) * s.boundingRadius) *
                                                h;
}

void PhysicsWorld::FindPairs() {
    boxes_.resize(broadBodies_.size());
    ParallelFor(0, broadBodies_.size(), kBodyGrain, boxAffinity_, [&](size_t k) {
        const SimBody& s = bodies_[broadBodies_[k]];
        const vec3 extent = WorldHalfExtent(s.collider, s.rotation) + vec3(Margin(s));
        BroadPhaseBox box{s.position - extent, s.position + extent, !s.dynamic};
        if (motion_[broadBodies_[k]] & kFresh) {
            // A static body just moved spans where it was too, so that sleepers there wake.
            const vec3 was = WorldHalfExtent(s.collider, glm::mat3_cast(s.previousOrientation)) +
                             vec3(Margin(s));
            box.min = glm::min(box.min, s.previousPosition - was);
            box.max = glm::max(box.max, s.previousPosition + was);
        }
        boxes_[k] = box;
    });
    sweep_.FindPairs(boxes_, pairs_, broadBodies_);
    // Solver slots in sweep order, then the bodies outside the broad phase (planes, bodies
    // without a collider) in body order.
    solverSlots_.resize(bodies_.size());
    sweep_.Ranks(broadBodies_, solverSlots_);
    auto outside = static_cast<uint32_t>(broadBodies_.size());
    for (const uint32_t i : outsideBodies_) solverSlots_[i] = outside++;
    stats_.lastPairs = static_cast<uint32_t>(pairs_.size());
}

void PhysicsWorld::IntegrateVelocities() {
    const float h = settings_.fixedStep;
    const float linearDamping = 1.0f / (1.0f + h * settings_.linearDamping);
    const float angularDamping = 1.0f / (1.0f + h * settings_.angularDamping);
    // The narrow phase changes no body, so each is handed to the solver here (GatherSolverBody),
    // while it is in this core's cache.
    solverBodies_.resize(bodies_.size());
    bodyStarts_.resize(bodies_.size());
    pseudoVelocities_.resize(bodies_.size());
    // The slots are scattered (sweep order): the lines a body ahead will write are fetched now,
    // so that their misses overlap.
    constexpr size_t kAhead = 8;
    ParallelFor(0, bodies_.size(), kBodyGrain, bodyAffinity_, [&](size_t i) {
        if (i + kAhead < bodies_.size()) {
            const uint32_t later = solverSlots_[i + kAhead];
            __builtin_prefetch(&solverBodies_[later], 1);
            __builtin_prefetch(&bodyStarts_[later], 1);
            __builtin_prefetch(reinterpret_cast<const char*>(&bodyStarts_[later] + 1) - 1, 1);
            __builtin_prefetch(&pseudoVelocities_[later], 1);
        }
        SimBody& s = bodies_[i];
        if (s.awake) {
            s.velocity = (s.velocity + settings_.gravity * h) * linearDamping;
            s.angularVelocity *= angularDamping;
            ClampLength(s.velocity, settings_.maxLinearSpeed);
            ClampLength(s.angularVelocity, settings_.maxAngularSpeed);
        }
        GatherSolverBody(s, solverSlots_[i], solverBodies_, bodyStarts_, pseudoVelocities_);
    });
    // The flags, not the bodies: 1 byte each instead of a cache line.
    stats_.lastAwake = static_cast<uint32_t>(
        std::count_if(motion_.begin(), motion_.end(), [](uint8_t m) { return (m & kAwake) != 0; }));
}

void PhysicsWorld::FindContacts() {
    CollideCandidates();
    LayOutContacts();
    stats_.lastContacts = static_cast<uint32_t>(contacts_.size());
    stats_.lastColors = batches_.Colors();
}

void PhysicsWorld::CollideCandidates() {
    const float h = settings_.fixedStep;
    const size_t bodyCount = bodies_.size();
    candidates_.resize(pairs_.size() + planes_.size() * bodyCount);
    candidatePoints_.resize(candidates_.size());
    candidateBodies_.resize(candidates_.size());
    const auto collidePair = [&](size_t k) {
        const auto [i, j] = pairs_[k];
        Candidate& out = candidates_[k];
        out.manifold.count = 0;
        const auto touch = [&](uint32_t first, uint32_t second, float lever) {
            candidateBodies_[k] = {first, second};
            out.rolling = RollingLimit(first, second, lever);
        };
        const SimBody& a = bodies_[i];
        const SimBody& b = bodies_[j];
        if (!a.awake && !b.awake) return;
        const float margin = settings_.contactMargin + glm::length(a.velocity - b.velocity) * h +
                             (glm::length(a.angularVelocity) * a.boundingRadius +
                              glm::length(b.angularVelocity) * b.boundingRadius) *
                                 h;
        const bool aSphere = a.collider.shape == ColliderShape::kSphere;
        const bool bSphere = b.collider.shape == ColliderShape::kSphere;
        Manifold& m = out.manifold;
        if (aSphere && bSphere) {
            if (CollideSpheres(a.position, a.collider.radius, b.position, b.collider.radius, margin,
                               m)) {
                touch(i, j, std::min(a.collider.radius, b.collider.radius));
                return;
            }
        } else if (aSphere) {
            if (CollideBoxSphere(BoxOf(b), a.position, a.collider.radius, margin, m)) {
                touch(j, i, a.collider.radius);
                return;
            }
        } else if (bSphere) {
            if (CollideBoxSphere(BoxOf(a), b.position, b.collider.radius, margin, m)) {
                touch(i, j, b.collider.radius);
                return;
            }
        } else if (CollideBoxes(BoxOf(a), BoxOf(b), margin, m)) {
            touch(i, j, 0.0f);
            return;
        }
        m.count = 0;
    };
    // Each candidate's number of points beside it, so that LayOutContacts finds the hits in a
    // byte array instead of a cache line per candidate.
    ParallelFor(0, pairs_.size(), kPairGrain, [&](size_t k) {
        collidePair(k);
        candidatePoints_[k] = static_cast<uint8_t>(candidates_[k].manifold.count);
    });
    for (size_t p = 0; p < planes_.size(); ++p) {
        const uint32_t planeBody = planes_[p];
        const SimBody& plane = bodies_[planeBody];
        PlaneShape shape;
        shape.normal = glm::normalize(plane.orientation * plane.collider.normal);
        shape.offset = glm::dot(shape.normal, plane.position);
        const size_t rowStart = pairs_.size() + p * bodyCount;
        Candidate* const row = candidates_.data() + rowStart;
        const auto collidePlane = [&](size_t i) {
            Candidate& out = row[i];
            out.manifold.count = 0;
            const SimBody& s = bodies_[i];
            if (!s.awake || !s.hasCollider) return;
            const float margin = settings_.contactMargin + glm::length(s.velocity) * h +
                                 glm::length(s.angularVelocity) * s.boundingRadius * h;
            const auto body = static_cast<uint32_t>(i);
            const auto touch = [&](float lever) {
                candidateBodies_[rowStart + i] = {planeBody, body};
                out.rolling = RollingLimit(planeBody, body, lever);
            };
            Manifold& m = out.manifold;
            if (s.collider.shape == ColliderShape::kSphere) {
                if (CollidePlaneSphere(shape, s.position, s.collider.radius, margin, m)) {
                    touch(s.collider.radius);
                    return;
                }
            } else if (s.collider.shape == ColliderShape::kBox) {
                if (CollidePlaneBox(shape, BoxOf(s), margin, m)) {
                    touch(0.0f);
                    return;
                }
            }
            m.count = 0;
        };
        uint8_t* const points = candidatePoints_.data() + rowStart;
        ParallelFor(0, bodyCount, kBodyGrain, bodyAffinity_, [&](size_t i) {
            collidePlane(i);
            points[i] = static_cast<uint8_t>(row[i].manifold.count);
        });
    }
}

void PhysicsWorld::LayOutContacts() {
    // Colours are assigned serially in candidate order. Within a colour the manifolds are then
    // ordered by region, the sweep rank of their moving body cut into kRegions: the solver splits
    // each colour evenly among its threads in that order, so a thread gets about the same region
    // in every colour and a body's cache line mostly stays with one core. A counting sort keeps
    // candidate order within a region: the layout depends only on the candidates, never on the
    // threads that found them.
    constexpr uint32_t kSlots = ContactColoring::kColors + 1;  // the colours and the overflow
    constexpr uint32_t kRegions = 256;
    // What the serial passes need of each hit is gathered in parallel first: they then read 28
    // bytes per hit in order instead of a candidate and two bodies' flags.
    const uint64_t ranks = std::max<uint64_t>(1, boxes_.size());
    hits_.resize(candidates_.size());
    hits_.resize(ParallelCompact(
        candidates_.size(), chunkStarts_, [&](size_t k) { return candidatePoints_[k] > 0; },
        [&](size_t k, uint32_t out) {
            const auto [first, second] = candidateBodies_[k];
            const bool firstMoves = (motion_[first] & kAwake) != 0;
            const bool secondMoves = (motion_[second] & kAwake) != 0;
            // A moving body has a collider, so its slot is its sweep rank.
            const uint64_t rank = solverSlots_[firstMoves ? first : second];
            Hit& hit = hits_[out];
            hit.candidate = static_cast<uint32_t>(k);
            hit.slot = static_cast<uint32_t>(rank * kRegions / ranks);
            hit.first = first;
            hit.second = second;
            hit.points = candidatePoints_[k];
            hit.firstMoves = firstMoves;
            hit.secondMoves = secondMoves;
        }));
    coloring_.Reset(static_cast<uint32_t>(bodies_.size()));
    slotManifolds_.assign(kSlots * kRegions, 0);
    slotPoints_.assign(kSlots * kRegions, 0);
    std::array<uint32_t, kSlots> colorManifolds{};
    for (Hit& hit : hits_) {
        const uint32_t color =
            coloring_.Assign(hit.first, hit.firstMoves, hit.second, hit.secondMoves);
        hit.slot += color * kRegions;  // the region, now with its colour
        // Places within the slot, made absolute once the slots' starts are known.
        hit.manifold = slotManifolds_[hit.slot]++;
        hit.firstPoint = slotPoints_[hit.slot];
        slotPoints_[hit.slot] += hit.points;
        ++colorManifolds[color];
    }
    batches_.colorBegin.assign(1, 0);
    batches_.lastIsOverflow = colorManifolds[ContactColoring::kOverflow] > 0;
    uint32_t manifoldTotal = 0;
    uint32_t pointTotal = 0;
    for (uint32_t color = 0; color < kSlots; ++color) {
        if (colorManifolds[color] == 0) continue;  // no hit reads its slots
        for (uint32_t slot = color * kRegions; slot < (color + 1) * kRegions; ++slot) {
            const uint32_t manifolds = slotManifolds_[slot];
            const uint32_t points = slotPoints_[slot];
            slotManifolds_[slot] = manifoldTotal;  // now where the slot's manifolds start
            slotPoints_[slot] = pointTotal;
            manifoldTotal += manifolds;
            pointTotal += points;
        }
        batches_.colorBegin.push_back(manifoldTotal);
    }
    batches_.manifoldBegin.resize(manifoldTotal + 1);
    batches_.manifoldBegin[manifoldTotal] = pointTotal;
    contacts_.resize(pointTotal);
    // The hits are in layout order now, their candidates scattered: those ahead are fetched.
    constexpr size_t kAhead = 8;
    ParallelFor(0, hits_.size(), kPairGrain, [&](size_t k) {
        if (k + kAhead < hits_.size()) {
            const auto later =
                reinterpret_cast<uintptr_t>(&candidates_[hits_[k + kAhead].candidate]);
            for (uintptr_t line = later & ~uintptr_t{63}; line < later + sizeof(Candidate);
                 line += 64) {
                _mm_prefetch(reinterpret_cast<const char*>(line), _MM_HINT_T0);
            }
        }
        Hit& hit = hits_[k];
        hit.manifold += slotManifolds_[hit.slot];
        hit.firstPoint += slotPoints_[hit.slot];
        batches_.manifoldBegin[hit.manifold] = hit.firstPoint;
        WriteContacts(candidates_[hit.candidate], hit.first, hit.second,
                      contacts_.data() + hit.firstPoint);
    });
}

float PhysicsWorld::RollingLimit(uint32_t first, uint32_t second, float lever) const {
    return lever * std::max(bodies_[first].rollingResistance, bodies_[second].rollingResistance);
}

void PhysicsWorld::WriteContacts(const Candidate& candidate, uint32_t first, uint32_t second,
                                 Contact* out) const {
    const Manifold& manifold = candidate.manifold;
    const float rolling = candidate.rolling;
    for (int k = 0; k < manifold.count; ++k) {
        out[k] = {first,
                  second,
                  manifold.normal,
                  manifold.points[k].point,
                  manifold.points[k].separation,
                  rolling,
                  0.0f,
                  0.0f,
                  0.0f};
    }
}

void PhysicsWorld::SeedFromLastStep() {
    const float maxDistance2 = settings_.warmStartDistance * settings_.warmStartDistance;
    // The manifolds' bodies are scattered, and so are their table slots: a manifold's bodies
    // are fetched two distances ahead and its slot one distance ahead, so that the misses
    // overlap.
    constexpr size_t kAhead = 8;
    const size_t manifolds = batches_.Manifolds();
    const auto firstContact = [&](size_t m) -> const Contact& {
        return contacts_[batches_.manifoldBegin[m]];
    };
    ParallelFor(0, manifolds, kPairGrain, [&](size_t m) {
        if (m + 2 * kAhead < manifolds) {
            const Contact& later = firstContact(m + 2 * kAhead);
            PrefetchPose(bodies_[later.a]);
            _mm_prefetch(reinterpret_cast<const char*>(&bodies_[later.b].entity), _MM_HINT_T0);
        }
        if (m + kAhead < manifolds) {
            const Contact& next = firstContact(m + kAhead);
            cache_.Prefetch(bodies_[next.a].entity, bodies_[next.b].entity);
        }
        const uint32_t begin = batches_.manifoldBegin[m];
        const uint32_t end = batches_.manifoldBegin[m + 1];
        const SimBody& a = bodies_[contacts_[begin].a];
        const std::span<const CachedContact> cached =
            cache_.Find(a.entity, bodies_[contacts_[begin].b].entity);
        if (cached.empty()) return;
        const glm::mat3 toLocal = glm::transpose(a.rotation);
        for (uint32_t k = begin; k < end; ++k) {
            Contact& c = contacts_[k];
            const vec3 local = toLocal * (c.point - a.position);
            const CachedContact* best = nullptr;
            float bestDistance2 = maxDistance2;
            for (const CachedContact& old : cached) {
                const vec3 d = old.localPoint - local;
                const float distance2 = glm::dot(d, d);
                if (distance2 < bestDistance2) {
                    bestDistance2 = distance2;
                    best = &old;
                }
            }
            if (best == nullptr) continue;
            c.normalImpulse = best->normalImpulse;
            c.tangentImpulse1 = best->tangentImpulse1;
            c.tangentImpulse2 = best->tangentImpulse2;
        }
    });
}

void PhysicsWorld::RememberImpulses() {
    // The contacts that pushed, in contact order (the same on any number of threads), so each
    // manifold's stay together.
    auto pushed = [&](size_t k) { return contacts_[k].normalImpulse > 0.0f; };
    std::vector<CachedContact>& entries = nextCache_.Entries();
    entries.resize(contacts_.size());
    // The contacts' bodies are scattered: those of the contacts ahead are fetched while this
    // one is written, as in the seeding.
    constexpr size_t kAhead = 8;
    const size_t n = contacts_.size();
    const uint32_t kept = ParallelCompact(n, chunkStarts_, pushed, [&](size_t k, uint32_t out) {
        if (k + kAhead < n) {
            const Contact& later = contacts_[k + kAhead];
            PrefetchPose(bodies_[later.a]);
            _mm_prefetch(reinterpret_cast<const char*>(&bodies_[later.b].entity), _MM_HINT_T0);
        }
        const Contact& c = contacts_[k];
        const SimBody& a = bodies_[c.a];
        entries[out] = {a.entity,
                        bodies_[c.b].entity,
                        glm::transpose(a.rotation) * (c.point - a.position),
                        c.normalImpulse,
                        c.tangentImpulse1,
                        c.tangentImpulse2};
    });
    entries.resize(kept);
    nextCache_.Index();
    std::swap(cache_, nextCache_);
}

void PhysicsWorld::IntegratePositions(bool anotherFollows) {
    const float h = settings_.fixedStep;
    const float linear2 = settings_.sleepLinearSpeed * settings_.sleepLinearSpeed;
    const float angular2 = settings_.sleepAngularSpeed * settings_.sleepAngularSpeed;
    const auto integrate = [&](SimBody& s, uint32_t slot) {
        s.velocity = solverBodies_[slot].velocity;
        s.angularVelocity = solverBodies_[slot].angularVelocity;
        const PseudoVelocity& pseudo = pseudoVelocities_[slot];
        s.position += (s.velocity + pseudo.linear) * h;
        const vec3 w = s.angularVelocity + pseudo.angular;
        // dq/dt = 1/2 (0, w) q, then renormalised.
        s.orientation = glm::normalize(s.orientation +
                                       glm::quat(0.0f, w.x, w.y, w.z) * s.orientation * (0.5f * h));
        // Sleep: a body slow for timeToSleep stops.
        const bool slow = glm::dot(s.velocity, s.velocity) < linear2 &&
                          glm::dot(s.angularVelocity, s.angularVelocity) < angular2;
        s.restingTime = slow ? s.restingTime + h : 0.0f;
        if (s.restingTime >= settings_.timeToSleep) {
            s.awake = false;
            s.velocity = vec3(0.0f);
            s.angularVelocity = vec3(0.0f);
        }
    };
    // Bodies in body order meet their solver slots in sweep order: the slots ahead are fetched.
    constexpr size_t kAhead = 8;
    ParallelFor(0, bodies_.size(), kBodyGrain, bodyAffinity_, [&](size_t i) {
        if (i + kAhead < bodies_.size()) {
            const uint32_t slot = solverSlots_[i + kAhead];
            _mm_prefetch(reinterpret_cast<const char*>(&solverBodies_[slot]), _MM_HINT_T0);
            _mm_prefetch(reinterpret_cast<const char*>(&pseudoVelocities_[slot]), _MM_HINT_T0);
        }
        SimBody& s = bodies_[i];
        if (s.awake) integrate(s, solverSlots_[i]);
        if (anotherFollows) StartStep(i);
    });
}

void AddPhysicsSystem(ecs::Scheduler& scheduler, PhysicsWorld& world) {
    scheduler.AddSystem("simulation", "physics",
                        [&world](Registry& registry, float dt) { world.Advance(registry, dt); });
}

}  // namespace rtrt::physics
