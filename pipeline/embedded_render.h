#pragma once
// A render for a program that embeds slowlight (the Python module): the scene and options are
// read and checked by the command line's own code (`slowlight render ARGS...` parsed by
// parse_command_line, the scene by load_scene or, for a scene given as JSON text, by
// parse_scene_text), then rendered by run_pipeline into the caller's frame sink, with the
// caller's progress and cancel flag. Nothing is written to disk, no signal handler is
// installed, and warnings are returned as lines instead of printed.
#include <atomic>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "config/run_options.h"
#include "config/scene_desc.h"
#include "pipeline/frame_sink.h"
#include "pipeline/memory_plan.h"
#include "pipeline/render_pipeline.h"
#include "stages/render/render_context.h"

namespace sl {

// A scene given as JSON text (a Python dict) rather than by a path on the command line.
struct SceneText {
    std::string json;
    std::string source_name = "<dict>";  // names it in messages
    std::string base_dir;                // resolves its mesh and model paths ("": the working directory)
};

// `render` or `info` followed by what the command line would take after it.
RunOptions embedded_options(const std::string& command, const std::vector<std::string>& args);

// The scene of `o` (its path, a model, or the built-in demo) or of `text`, with every imported
// file read and the command line's overrides applied: load_scene's steps.
SceneDesc embedded_scene(const RunOptions& o, const std::optional<SceneText>& text);

class EmbeddedRender {
public:
    // Throws InputError with the command line's message for whatever `slowlight render` refuses
    // before rendering (outputs aside: this render writes none).
    EmbeddedRender(const std::vector<std::string>& args, const std::optional<SceneText>& text);

    const RunOptions& options() const { return o_; }
    const SceneDesc& scene() const { return scene_; }
    const RenderContext& context() const { return *ctx_; }
    const MemoryPlan& plan() const { return plan_; }
    // "warning: ..." lines, as the command line prints them: the imported files', the scene's,
    // and after run() the steady-black one.
    const std::vector<std::string>& warnings() const { return warnings_; }

    // Every section into `sink`, the exposure decided as for a video (unless --exposure fixed it:
    // the sink is then told that value). Interrupted by `cancel`: the pass in flight ends and
    // the section in progress is written from the passes it completed, as the program does.
    PipelineStats run(FrameSink& sink, const ProgressFn& progress, const std::atomic<bool>& cancel);

    // The --stats file's numbers for this run.
    nlohmann::json stats(const PipelineStats& stats, double exposure) const;

private:
    RunOptions o_;
    SceneDesc scene_;
    MemoryPlan plan_;
    std::unique_ptr<RenderContext> ctx_;
    std::vector<std::string> warnings_;
    double setup_seconds_ = 0, wall_seconds_ = 0;
};

}  // namespace sl
