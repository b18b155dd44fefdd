#pragma once
// What every rtrt command shares, the benchmarks included: exit statuses and option parsers.
#include <cstdint>
#include <optional>
#include <string>

#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/output_transform.h"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace rtrt {

class World;

// Exit statuses scripts can rely on.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;   // the work itself failed (GPU error, I/O error)
inline constexpr int kExitBadInput = 2;  // bad command line, scene, model or output path

// Puts the exit statuses at the end of the --help of APP and of every command under it (after a
// command's own footer, where it has one).
void AddExitStatusHelp(CLI::App& app);

// A number option's check: finite and within [min, max]. CLI::Range lets NaN through, as both of
// its comparisons are false for it.
CLI::Validator FiniteRange(double min, double max);

// Checks every option of APP and its subcommands takes: integers and numbers in decimal only
// (CLI11 reads integers in C's base 0: "017" was 15, "0x10" 16, a negative wrapped in an unsigned
// option; and numbers with strtod's hexadecimal floats), and no empty text. Call once every
// option is added.
void CheckOptionValues(CLI::App& app);

// A file option's check, when the command line is read and so before any work: the file can be
// written whole (CheckOutputPath: its folder exists, it is not a folder or a device).
CLI::Validator WritableFile();

// InputError (exit 2) for a command line whose outputs (-o, --csv, --manifest, --record) name one
// of its input files (the positional arguments, --script) or each other: the command would have
// written over the scene it read, or one report over another. For the parsed subcommands of
// APP, once the command line is read and before any of them runs.
void RefuseOutputsOverInputs(const CLI::App& app);

// Parses WIDTHxHEIGHT (1..16384 each); InputError naming --size otherwise.
void ParseSize(const std::string& text, uint32_t* width, uint32_t* height);

// --frames: "N" means frames 0 to N-1, "A:B" frames A to B-1 (A < B <= 10,000,000); false when
// malformed.
inline constexpr int kMaxFrames = 10000000;
bool ParseFrames(const std::string& text, int* first, int* end);
// Why ParseFrames refuses TEXT ("" when it takes it): malformed, reversed or beyond kMaxFrames.
std::string FramesProblem(const std::string& text);

// --exposure EV and --tone-map NAME, over what the scene says (its "colours", "exposure" and
// "tone_map"); absent, the scene's own.
struct OutputOptions {
    std::optional<float> exposureEv;
    std::string toneMap;
};
void AddOutputOptions(CLI::App* command, OutputOptions* options);
OutputTransform ResolveOutput(OutputTransform scene, const OutputOptions& options);

// --gpus N|all: the GPUs each CUDA frame is split over (default 1, the current device).
void AddGpusOption(CLI::App* command, std::string* gpus);
// The split --gpus names for `backend`; InputError naming --gpus for a count this machine does
// not have, or for more than one GPU on the CPU back end.
GpuSplit ResolveGpus(const std::string& gpus, Backend backend);

// --traversal auto|nested|single: the CUDA back end's scene traversal for scenes of many
// instances (traversal/traversal_form.h; default auto).
void AddTraversalOption(CLI::App* command, std::string* traversal);
// InputError naming --traversal when a form other than auto is asked of the CPU back end, which
// has one traversal and had ignored the option.
void CheckTraversalBackend(const std::string& traversal, Backend backend);

// --physics-solver cpu|gpu: where the rigid bodies' contacts are solved (default cpu; gpu gives
// the same bits, see gpu_contact_solver.h).
void AddPhysicsSolverOption(CLI::App* command, std::string* solver);
// InputError naming --physics-solver when solver is "gpu" and this machine cannot solve on its
// GPU.
void CheckPhysicsSolver(const std::string& solver);
// Moves world's contact solver to the GPU when solver is "gpu"; InputError naming
// --physics-solver when this machine has no CUDA device for it.
void ApplyPhysicsSolver(const std::string& solver, World& world);

}  // namespace rtrt
