// The traversal form's choice (traversal/traversal_form.h) fed with made-up trace times: trials
// alternate the forms, the faster is kept only beyond the margin, trials come again after the
// settled frames and at once on a new configuration, and late or stale times do not confuse it.
#include <gtest/gtest.h>

#include <deque>

#include "engine/render_rt/traversal/traversal_form.h"

namespace rtrt {
namespace {

using Ticket = TraversalChooser::Ticket;

// Plays `frames` frames whose traces take nestedMs or singleMs, each time reported `lag` frames
// after its frame was issued (as the GPU's events are read); returns how many took the single
// loop.
uint32_t Play(TraversalChooser& chooser, uint32_t frames, double nestedMs, double singleMs,
              uint32_t lag = 2, uint64_t configuration = 1) {
    std::deque<Ticket> inFlight;
    uint32_t single = 0;
    for (uint32_t f = 0; f < frames; ++f) {
        const Ticket t = chooser.Next(configuration);
        single += t.singleLoop ? 1 : 0;
        inFlight.push_back(t);
        if (inFlight.size() > lag) {
            const Ticket done = inFlight.front();
            inFlight.pop_front();
            chooser.Report(done, done.singleLoop ? singleMs : nestedMs);
        }
    }
    return single;
}

TEST(TraversalChooser, TrialAlternatesTheFormsStartingWithTheOneInUse) {
    TraversalChooser chooser;
    for (uint32_t f = 0; f < TraversalChooser::kTrialFrames; ++f) {
        const Ticket t = chooser.Next(7);
        EXPECT_EQ(t.trial, 1u) << "frame " << f;
        EXPECT_EQ(t.singleLoop, f % 2 == 1) << "frame " << f;
    }
    // Its times not in yet: the frames after take the form in use, outside the trial.
    const Ticket after = chooser.Next(7);
    EXPECT_EQ(after.trial, 0u);
    EXPECT_FALSE(after.singleLoop);
    EXPECT_EQ(chooser.Decisions(), 0u);
}

TEST(TraversalChooser, KeepsTheFasterForm) {
    TraversalChooser single;
    Play(single, 20, 2.0, 1.0);
    EXPECT_EQ(single.Decisions(), 1u);
    EXPECT_TRUE(single.SettledOnSingleLoop());
    EXPECT_TRUE(single.Next(1).singleLoop);
    TraversalChooser nested;
    Play(nested, 20, 1.0, 2.0);
    EXPECT_EQ(nested.Decisions(), 1u);
    EXPECT_FALSE(nested.SettledOnSingleLoop());
}

TEST(TraversalChooser, SwitchesOnlyBeyondTheMargin) {
    const double within = 1.0 - 0.5 * TraversalChooser::kSwitchMargin;
    const double beyond = 1.0 - 2.0 * TraversalChooser::kSwitchMargin;
    TraversalChooser chooser;
    Play(chooser, 20, 1.0, within);
    EXPECT_FALSE(chooser.SettledOnSingleLoop());
    TraversalChooser other;
    Play(other, 20, 1.0, beyond);
    EXPECT_TRUE(other.SettledOnSingleLoop());
    // Settled on the single loop, the nested form now needs the margin to take over again.
    Play(other, TraversalChooser::kSettledFrames + 20, beyond * within, beyond);
    EXPECT_EQ(other.Decisions(), 2u);
    EXPECT_TRUE(other.SettledOnSingleLoop());
}

TEST(TraversalChooser, MedianIgnoresOneSlowFrame) {
    // The first launch of a kernel can be slow (lazy module loading): here the single loop's
    // first trial frame takes 9 ms against 1 ms for its others and 1.5 ms for the nested form.
    TraversalChooser chooser;
    uint32_t f = 0;
    std::deque<Ticket> inFlight;
    while (chooser.Decisions() == 0 && f < 40) {
        const Ticket t = chooser.Next(1);
        inFlight.push_back(t);
        if (inFlight.size() > 1) {
            const Ticket done = inFlight.front();
            inFlight.pop_front();
            const bool first = f < 3;
            chooser.Report(done, done.singleLoop ? (first ? 9.0 : 1.0) : 1.5);
        }
        ++f;
    }
    EXPECT_EQ(chooser.Decisions(), 1u);
    EXPECT_TRUE(chooser.SettledOnSingleLoop());
}

TEST(TraversalChooser, TriesAgainAfterTheSettledFramesAndFollowsTheScene) {
    TraversalChooser chooser;
    Play(chooser, 20, 2.0, 1.0);
    ASSERT_TRUE(chooser.SettledOnSingleLoop());
    // The scene changes: now the nested form is faster. The next trial finds it.
    const uint32_t single = Play(chooser, TraversalChooser::kSettledFrames + 20, 1.0, 2.0);
    EXPECT_EQ(chooser.Decisions(), 2u);
    EXPECT_FALSE(chooser.SettledOnSingleLoop());
    // Settled frames on the single loop, then half of the trial's frames, then the nested form.
    EXPECT_LT(single, TraversalChooser::kSettledFrames);
    EXPECT_GT(single, TraversalChooser::kSettledFrames - 20);
}

TEST(TraversalChooser, NewConfigurationStartsATrialAtOnce) {
    TraversalChooser chooser;
    Play(chooser, 20, 2.0, 1.0, 2, 1);
    ASSERT_EQ(chooser.Decisions(), 1u);
    const Ticket t = chooser.Next(2);
    EXPECT_EQ(t.trial, 2u);
    EXPECT_TRUE(t.singleLoop) << "the form in use first";
    EXPECT_FALSE(chooser.Next(2).singleLoop);
}

TEST(TraversalChooser, StaleAndMissingTimesAreIgnored) {
    TraversalChooser chooser;
    std::vector<Ticket> first;
    for (uint32_t f = 0; f < TraversalChooser::kTrialFrames; ++f) first.push_back(chooser.Next(1));
    // The configuration changes before any time arrived: the first trial's times are stale.
    const Ticket fresh = chooser.Next(2);
    for (const Ticket& t : first) chooser.Report(t, t.singleLoop ? 0.1 : 5.0);
    EXPECT_EQ(chooser.Decisions(), 0u);
    // Frames not traced as a trial report nothing that counts, nor do bad times.
    chooser.Report(Ticket{}, 0.1);
    chooser.Report(fresh, -1.0);
    EXPECT_EQ(chooser.Decisions(), 0u);
    // The second trial's times never arrive, nor do those of the trials after it that these
    // frames start; then times arrive again, and the trial of those frames decides.
    for (int f = 0; f < 40; ++f) chooser.Next(2);
    EXPECT_EQ(chooser.Decisions(), 0u);
    const uint32_t single = Play(chooser, 60, 2.0, 1.0, 2, 2);
    EXPECT_GT(single, 0u);
    EXPECT_EQ(chooser.Decisions(), 1u);
    EXPECT_TRUE(chooser.SettledOnSingleLoop());
}

TEST(TraversalForm, NamesAndFeatures) {
    for (TraversalForm f :
         {TraversalForm::kAuto, TraversalForm::kNested, TraversalForm::kSingleLoop}) {
        TraversalForm parsed;
        ASSERT_TRUE(ParseTraversalForm(TraversalFormName(f), &parsed));
        EXPECT_EQ(parsed, f);
    }
    TraversalForm unused;
    EXPECT_FALSE(ParseTraversalForm("wide", &unused));
    const uint32_t shaded = kFeatureShadows | kFeatureReflection;
    const uint32_t many = shaded | kFeatureManyInstances;
    EXPECT_EQ(WithTraversalForm(many, TraversalForm::kSingleLoop), many);
    EXPECT_EQ(WithTraversalForm(many, TraversalForm::kNested), shaded);
    EXPECT_EQ(WithTraversalForm(many, TraversalForm::kAuto), shaded) << "unmeasured: nested";
    // Scenes of few instances take the nested form whatever is asked.
    for (TraversalForm f :
         {TraversalForm::kAuto, TraversalForm::kNested, TraversalForm::kSingleLoop})
        EXPECT_EQ(WithTraversalForm(shaded, f), shaded);
}

}  // namespace
}  // namespace rtrt
