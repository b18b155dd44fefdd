#pragma once
// Graph colouring of a step's contacts, so that the solver can run them in parallel and still get
// the same answer on any number of threads: manifolds (the contacts of one pair of bodies) of one
// colour share no awake body, so solving them in any order, or at once, does the same arithmetic
// on the same values. Colours are solved one after another, like the serial Gauss-Seidel sweep
// over a fixed order that they replace.
#include <bit>
#include <cstdint>
#include <vector>

namespace rtrt::physics {

// A step's contacts laid out colour by colour: manifold m's contacts are
// [manifoldBegin[m], manifoldBegin[m + 1]); colour c's manifolds are
// [colorBegin[c], colorBegin[c + 1]). The last colour may be the overflow (see ContactColoring).
//
// Each colour's manifolds may also be ordered by region (where their moving body lies): the solver
// cuts every colour into its threads' shares in that order, so that a thread meets about the same
// bodies in every colour and they stay in its core's cache.
struct ContactBatches {
    std::vector<uint32_t> manifoldBegin{0};
    std::vector<uint32_t> colorBegin{0};
    bool lastIsOverflow = false;  // its manifolds may share bodies: solve it serially, in order

    uint32_t Colors() const { return static_cast<uint32_t>(colorBegin.size() - 1); }
    uint32_t Manifolds() const { return static_cast<uint32_t>(manifoldBegin.size() - 1); }
};

// Greedy colouring in the order the manifolds are offered (Box2D v3's constraint graph does the
// same with a bit set per body): each takes the lowest colour that neither of its awake bodies
// has used. A body that does not move (static, sleeping) is only read by the solver, so it
// constrains nothing: the floor under a thousand bodies does not serialise them. A manifold whose
// bodies have used all kColors colours goes to the overflow, solved serially after the colours.
class ContactColoring {
  public:
    static constexpr uint32_t kColors = 64;
    static constexpr uint32_t kOverflow = kColors;

    // Forgets every colour; bodies are indices below bodyCount.
    void Reset(uint32_t bodyCount);
    // The colour of a manifold between bodies a and b (kOverflow when none is left); aMoves and
    // bMoves say whether the solver changes that body's velocities.
    uint32_t Assign(uint32_t a, bool aMoves, uint32_t b, bool bMoves) {
        const uint64_t taken = (aMoves ? used_[a] : 0) | (bMoves ? used_[b] : 0);
        if (taken == ~uint64_t{0}) return kOverflow;
        const auto color = static_cast<uint32_t>(std::countr_one(taken));
        const uint64_t bit = uint64_t{1} << color;
        if (aMoves) used_[a] |= bit;
        if (bMoves) used_[b] |= bit;
        return color;
    }

  private:
    std::vector<uint64_t> used_;  // per body, a bit per colour its manifolds have
};

}  // namespace rtrt::physics
