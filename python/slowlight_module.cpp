// The C++ half of `import slowlight` (_slowlight): one render at a time as an object whose
// frames, progress and end the Python half (python/slowlight/__init__.py) collects in its own
// thread. The render runs on a thread of its own with the GIL released; a frame sink hands its
// frames either into one preallocated float32 array (render()) or, one at a time and without a
// copy (the pipeline's buffer itself, swapped for one Python dropped), through a bounded queue (frames(): at most `queue_frames` frames wait for Python, so a slow consumer
// holds the pipeline's write stage instead of letting frames pile up).
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "foundation/constants.h"
#include "foundation/errors.h"
#include "foundation/message_lines.h"
#include "foundation/warning_lines.h"
#include "pipeline/embedded_render.h"
#include "pipeline/memory_plan.h"
#include "pipeline/scene_info.h"

namespace py = pybind11;

namespace sl {
namespace {

// What the command line prints after "error: " (one line, at most its length).
std::string error_text(const std::exception& e) { return message_line("error: ", e.what()).substr(7); }

std::optional<SceneText> scene_text(const std::optional<std::string>& json, const std::string& base_dir) {
    if (!json) return std::nullopt;
    SceneText t;
    t.json = *json;
    t.base_dir = base_dir;
    return t;
}

// Pixel buffers Python dropped, swapped into the pipeline for the next frame: a fresh 25 MB
// buffer per 1080p frame cost its pages' first-touch faults every frame (on this kind of
// machine eight times the copy itself), where the program reuses its frame buffers.
struct FramePool {
    std::mutex m;
    std::vector<std::vector<float>> free;
    size_t keep = 4;
    std::vector<float> take() {
        std::lock_guard lock(m);
        if (free.empty()) return {};
        std::vector<float> v = std::move(free.back());
        free.pop_back();
        return v;
    }
    void give(std::vector<float>&& v) {
        std::lock_guard lock(m);
        if (free.size() < keep) free.push_back(std::move(v));
    }
};

struct PooledPixels {
    std::vector<float> rgb;
    std::shared_ptr<FramePool> pool;  // null: not pooled
};

// A frame's pixels as an array that owns them (no copy); back to the pool when Python drops it.
py::array_t<float> owned_image(std::vector<float>&& rgb, int height, int width,
                               std::shared_ptr<FramePool> pool = nullptr) {
    auto* owner = new PooledPixels{std::move(rgb), std::move(pool)};
    py::capsule free_it(owner, [](void* p) {
        auto* o = static_cast<PooledPixels*>(p);
        if (o->pool) o->pool->give(std::move(o->rgb));
        delete o;
    });
    return py::array_t<float>({height, width, 3}, owner->rgb.data(), free_it);
}

// float32 (frames, height, width, 3) in memory of its own, its pages mapped at once
// (MAP_POPULATE): render()'s array was otherwise first touched page by page as the frames
// arrived, and those faults cost more than the copies (docs/benchmarks.md: 1.2 GB filled in
// 1.6-8.0 s with 4 KiB faults, 1.1 s mapping + 0.2 s filling when populated; huge pages, with
// their compaction, were slower still).
py::array_t<float> frames_array(int frames, int height, int width) {
    struct Mapping {
        void* p;
        size_t bytes;
    };
    const size_t bytes = std::max<size_t>(1, static_cast<size_t>(frames) * height * width * 3 * sizeof(float));
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && page > 0 && bytes > static_cast<size_t>(pages) * static_cast<size_t>(page))
        throw InputError("render() keeps every frame: " + format_bytes(bytes) + " for " + std::to_string(frames) +
                         " frames, more than this machine's " +
                         format_bytes(static_cast<uint64_t>(pages) * static_cast<uint64_t>(page)) +
                         "; stream them with slowlight.frames(), or use fewer frames or a smaller image");
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    auto* m = new Mapping{p, bytes};
    py::capsule unmap(m, [](void* q) {
        auto* mm = static_cast<Mapping*>(q);
        munmap(mm->p, mm->bytes);
        delete mm;
    });
    return py::array_t<float>({frames, height, width, 3}, static_cast<float*>(p), unmap);
}

class Render;

// The pipeline's write stage calls this, one frame at a time, in index order.
class ModuleSink : public FrameSink {
public:
    explicit ModuleSink(Render& r) : r_(r) {}
    bool needs_exposure() const override { return !exposure_; }
    void set_exposure_plan(const ExposurePlan& plan) override {
        exposure_ = plan.base;
        per_frame_ = plan.per_frame;
    }
    std::optional<double> exposure() const override { return exposure_; }
    void write_frame(int index, const std::vector<float>& rgb, bool, const Metadata&) override;
    void take_frame(int index, std::vector<float>& rgb, bool, const Metadata&) override;
    void write_steady(const std::vector<float>& rgb, const Metadata&) override;

    std::optional<double> exposure_;
    std::vector<double> per_frame_;

private:
    Render& r_;
};

class Render {
public:
    Render(const std::vector<std::string>& args, const std::optional<std::string>& json, const std::string& base_dir)
        : render_(args, scene_text(json, base_dir)), sink_(*this) {}

    ~Render() {
        abandon();
        py::gil_scoped_release unlocked;
        if (worker_.joinable()) worker_.join();
    }

    int frames() const { return render_.context().timeline.frames; }
    int width() const { return render_.context().width; }
    int height() const { return render_.context().height; }
    int sections() const { return render_.plan().sections; }
    int passes() const { return render_.scene().render.passes; }
    std::vector<double> edges_ns() const {
        std::vector<double> e;
        for (int k = 0; k <= frames(); ++k) e.push_back(render_.context().timeline.edge(k));
        return e;
    }
    std::vector<std::string> warnings() const {
        std::lock_guard lock(m_);
        return render_.warnings();
    }

    // `into`: a C-contiguous float32 array (frames, height, width, 3) the frames are written
    // into; None: frames are queued for next_event, at most `queue_frames` at a time.
    void start(py::object into, int queue_frames, bool progress) {
        if (worker_.joinable()) throw std::logic_error("this render was already started");
        if (!into.is_none()) {
            auto a = into.cast<py::array_t<float, py::array::c_style>>();
            if (a.ndim() != 4 || a.shape(0) != frames() || a.shape(1) != height() || a.shape(2) != width() || a.shape(3) != 3)
                throw std::invalid_argument("the frames array has the wrong shape");
            into_ = a;
            into_data_ = a.mutable_data();
        }
        queue_frames_ = std::max(1, queue_frames);
        pool_->keep = static_cast<size_t>(queue_frames_) + 2;
        progress_ = progress;
        worker_ = std::thread([this] { work(); });
    }

    // The next thing that happened: ("frame", index, image), ("progress", section, pass),
    // ("done",), or None when nothing did within `timeout` seconds. A failure of the render is
    // raised here (ValueError for bad input, RuntimeError otherwise).
    py::object next_event(double timeout) {
        std::unique_lock lock(m_);
        {
            py::gil_scoped_release unlocked;
            cv_.wait_for(lock, std::chrono::duration<double>(timeout),
                         [&] { return !queue_.empty() || !progress_events_.empty() || done_; });
        }
        if (!progress_events_.empty()) {
            const auto [s, p] = progress_events_.front();
            progress_events_.pop_front();
            return py::make_tuple("progress", s, p);
        }
        if (!queue_.empty()) {
            auto [index, rgb] = std::move(queue_.front());
            queue_.pop_front();
            cv_.notify_all();  // room in the queue
            lock.unlock();
            return py::make_tuple("frame", index, owned_image(std::move(rgb), height(), width(), pool_));
        }
        if (done_) {
            if (error_) std::rethrow_exception(error_);
            return py::make_tuple("done");
        }
        return py::none();
    }

    // Ctrl-C: the pass in flight ends, the section in progress is written from the passes it had.
    void cancel() { cancel_ = true; }
    // Nobody will read the frames any more: stop as soon as possible and drop them.
    void abandon() {
        std::lock_guard lock(m_);
        cancel_ = true;
        abandoned_ = true;
        queue_.clear();
        cv_.notify_all();
    }

    int frames_written() const { return frames_written_; }
    bool interrupted() const { return stats_.interrupted; }
    py::object steady() {
        std::lock_guard lock(m_);
        if (steady_.empty()) return py::none();
        return owned_image(std::vector<float>(steady_), height(), width());
    }
    py::object exposure() const { return sink_.exposure_ ? py::cast(*sink_.exposure_) : py::none(); }
    std::vector<double> per_frame_exposure() const { return sink_.per_frame_; }
    std::string stats_json() const { return render_.stats(stats_, sink_.exposure_.value_or(1.0)).dump(); }

    // Called by the sink on the render's thread. Streaming, the frame's own buffer goes to the
    // queue and the pipeline gets one that Python dropped (or none: it then allocates).
    void frame(int index, std::vector<float>& rgb) {
        if (into_data_) {
            const size_t n = rgb.size();
            std::memcpy(into_data_ + static_cast<size_t>(index) * n, rgb.data(), n * sizeof(float));
            frames_written_ = index + 1;
            return;
        }
        std::unique_lock lock(m_);
        cv_.wait(lock, [&] { return queue_.size() < static_cast<size_t>(queue_frames_) || abandoned_; });
        if (abandoned_) return;
        std::vector<float> pixels = pool_->take();
        pixels.swap(rgb);
        queue_.emplace_back(index, std::move(pixels));
        frames_written_ = index + 1;
        cv_.notify_all();
    }
    void steady_image(const std::vector<float>& rgb) {
        std::lock_guard lock(m_);
        steady_ = rgb;
    }

private:
    void work() {
        try {
            ProgressFn progress;
            if (progress_)
                progress = [this](int s, int p) {
                    std::lock_guard lock(m_);
                    progress_events_.emplace_back(s, p);
                    cv_.notify_all();
                };
            stats_ = render_.run(sink_, progress, cancel_);
        } catch (...) {
            error_ = std::current_exception();
        }
        std::lock_guard lock(m_);
        done_ = true;
        cv_.notify_all();
    }

    EmbeddedRender render_;
    ModuleSink sink_;
    py::object into_;
    float* into_data_ = nullptr;
    int queue_frames_ = 2;
    bool progress_ = false;
    std::thread worker_;
    mutable std::mutex m_;
    std::condition_variable cv_;
    std::deque<std::pair<int, std::vector<float>>> queue_;
    std::shared_ptr<FramePool> pool_ = std::make_shared<FramePool>();
    std::deque<std::pair<int, int>> progress_events_;
    std::vector<float> steady_;
    std::atomic<bool> cancel_{false};
    bool abandoned_ = false;
    bool done_ = false;
    std::exception_ptr error_;
    std::atomic<int> frames_written_{0};
    PipelineStats stats_;
};

void ModuleSink::write_frame(int index, const std::vector<float>& rgb, bool on_disk, const Metadata& extra) {
    std::vector<float> copy(rgb);
    take_frame(index, copy, on_disk, extra);
}
void ModuleSink::take_frame(int index, std::vector<float>& rgb, bool, const Metadata&) { r_.frame(index, rgb); }
void ModuleSink::write_steady(const std::vector<float>& rgb, const Metadata&) { r_.steady_image(rgb); }

std::string info_json(const std::vector<std::string>& args, const std::optional<std::string>& json, const std::string& base_dir) {
    const RunOptions o = embedded_options("info", args);
    std::vector<std::string> warnings;  // the imported files' first, as the program prints them
    SceneDesc scene;
    {
        ScopedWarningSink imports([&](const std::string& line) { warnings.push_back(line); });
        scene = embedded_scene(o, scene_text(json, base_dir));
    }
    nlohmann::json j = scene_info_json(scene, o);
    for (const auto& w : j["warnings"]) warnings.push_back(w.get<std::string>());
    j["warnings"] = warnings;
    return j.dump();
}

}  // namespace
}  // namespace sl

PYBIND11_MODULE(_slowlight, m) {
    using sl::Render;
    // As the program does (pipeline/main.cpp): one malloc arena, and large blocks (frames,
    // photon maps) from mmap, returned to the system when freed, so that a long streamed render
    // does not creep up section after section.
    mallopt(M_ARENA_MAX, 1);
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);
    m.doc() = "slowlight's renderer (the C++ half of the slowlight package)";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const sl::InputError& e) {
            PyErr_SetString(PyExc_ValueError, sl::error_text(e).c_str());
        } catch (const sl::RuntimeFailure& e) {
            PyErr_SetString(PyExc_RuntimeError, sl::error_text(e).c_str());
        }
    });
    m.attr("SPEED_OF_LIGHT_M_PER_NS") = sl::kSpeedOfLight;
    m.attr("VERSION") = SLOWLIGHT_VERSION;
    m.def("frames_array", &sl::frames_array, py::arg("frames"), py::arg("height"), py::arg("width"));
    m.def("info_json", &sl::info_json, py::arg("args"), py::arg("json"), py::arg("base_dir"),
          py::call_guard<py::gil_scoped_release>());
    py::class_<Render>(m, "Render")
        .def(py::init<const std::vector<std::string>&, const std::optional<std::string>&, const std::string&>(),
             py::arg("args"), py::arg("json"), py::arg("base_dir"), py::call_guard<py::gil_scoped_release>())
        .def_property_readonly("frames", &Render::frames)
        .def_property_readonly("width", &Render::width)
        .def_property_readonly("height", &Render::height)
        .def_property_readonly("sections", &Render::sections)
        .def_property_readonly("passes", &Render::passes)
        .def_property_readonly("edges_ns", &Render::edges_ns)
        .def_property_readonly("warnings", &Render::warnings)
        .def("start", &Render::start, py::arg("into"), py::arg("queue_frames"), py::arg("progress"))
        .def("next_event", &Render::next_event, py::arg("timeout"))
        .def("cancel", &Render::cancel)
        .def("abandon", &Render::abandon)
        .def_property_readonly("frames_written", &Render::frames_written)
        .def_property_readonly("interrupted", &Render::interrupted)
        .def_property_readonly("steady", &Render::steady)
        .def_property_readonly("exposure", &Render::exposure)
        .def_property_readonly("per_frame_exposure", &Render::per_frame_exposure)
        .def("stats_json", &Render::stats_json);
}
