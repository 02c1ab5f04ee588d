// The step workspace (docs/architecture.md, "Model and state"): a steady-state step allocates
// nothing. This executable replaces the global operator new (and its variants) with a counting
// one, runs every reference scene (apps/scenes/*.json, each with its own integrator, explicit or
// implicit) for a warm-up — the first steps size the workspace: step matrices, constraint
// columns, contact lists — then runs the next 100 steps, goes back to their start and counts heap
// allocations while it runs them again: buffers sized by a count that changes from step to step
// (contacts) grow geometrically when it reaches a new maximum, and never otherwise. Any count
// above zero fails, naming the scene. A scene whose points change as it runs (adaptive
// refinement lays it out anew, and that allocates) is counted once its layout has stopped
// changing for a whole window.
//
// Its own executable (label "workspace"): the replaced operator new must not count the other
// modules' tests.
#include <gtest/gtest.h>

#include <execinfo.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <string>
#include <vector>

#include "filum/all_components.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
// FILUM_TRACE_ALLOCATIONS=1: print the call stack of each counted allocation to stderr (resolve
// with addr2line -f -C -e build/tests/test_workspace ADDRESS).
const bool trace = std::getenv("FILUM_TRACE_ALLOCATIONS") != nullptr;

void noteAllocation() {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (!trace) return;
  counting = false;  // backtrace itself may allocate
  void* frames[24];
  backtrace_symbols_fd(frames, backtrace(frames, 24), 2);
  counting = true;
}

/// Counts and allocates; nullptr when memory is exhausted (the throwing forms throw then).
void* allocateOrNull(std::size_t size, std::size_t alignment = 0) noexcept {
  if (counting.load(std::memory_order_relaxed)) noteAllocation();
  if (size == 0) size = 1;
  return alignment > alignof(std::max_align_t) ? std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment)
                                               : std::malloc(size);
}

void* allocate(std::size_t size, std::size_t alignment = 0) {
  void* p = allocateOrNull(size, alignment);
  if (!p) throw std::bad_alloc();
  return p;
}
}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, std::align_val_t a) { return allocate(size, static_cast<std::size_t>(a)); }
void* operator new[](std::size_t size, std::align_val_t a) { return allocate(size, static_cast<std::size_t>(a)); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return allocateOrNull(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return allocateOrNull(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace filum {
namespace {

std::vector<std::string> referenceScenes() {
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(FILUM_SOURCE_DIR) + "/apps/scenes"))
    if (entry.path().extension() == ".json") paths.push_back(entry.path().string());
  std::sort(paths.begin(), paths.end());
  return paths;
}

/// Heap allocations during `steps` steps after `warmup` steps of the scene at `path`, with its
/// integrator replaced by `integrator` unless null.
long allocationsInSteadySteps(const std::string& path, const nlohmann::json& integrator, int warmup, int steps) {
  nlohmann::json document = readJsonFile(path);
  if (!integrator.is_null()) document["integrator"] = integrator;
  std::unique_ptr<Scene> scene = loadScene(document, path, app::makeFactory());
  scene->init();
  for (int k = 0; k < warmup; ++k) {
    const StepReport report = scene->step();
    EXPECT_TRUE(report.ok) << path << ": " << report.message;
    if (!report.ok) return -1;
  }
  // The window is run once to size the workspace for what happens in it (a contact set reaching
  // a new size grows its buffers once), then again from the same state, counted: a step whose
  // sizes were reached before must not allocate. (The rerun is bit-identical: determinism.)
  // A scene that changes its points as it runs (adaptive refinement) is steady once its layout
  // stops changing: windows are run until one passes without a layout change (a saved state of
  // another layout would not fit), at most kWindows of them.
  constexpr int kWindows = 20;
  SceneState window_start = scene->state();
  bool ok = true;
  for (int window = 0; window < kWindows; ++window) {
    window_start = scene->state();
    const long revision = scene->layoutRevision();
    for (int k = 0; k < steps && ok; ++k) ok = scene->step().ok;
    if (scene->layoutRevision() == revision) break;
    EXPECT_LT(window, kWindows - 1) << path << ": its layout still changes after " << kWindows << " windows";
  }
  scene->setState(window_start);
  allocations = 0;
  counting = true;
  for (int k = 0; k < steps && ok; ++k) ok = scene->step().ok;
  counting = false;
  EXPECT_TRUE(ok) << path << " failed a step while allocations were counted";
  return allocations.load();
}

TEST(SteadyStep, NoReferenceSceneAllocatesInASteadyStep) {
  // Warm-up of 200 steps: the first contacts of the contact scenes form.
  for (const std::string& path : referenceScenes()) {
    const long count = allocationsInSteadySteps(path, nullptr, 200, 100);
    std::printf("  %-60s %ld allocations in 100 steps\n", std::filesystem::path(path).filename().c_str(), count);
    EXPECT_EQ(count, 0) << path;
  }
}

TEST(SteadyStep, EveryIntegratorStepsTheHangingThreadWithoutAllocating) {
  // The soft-spring thread: the explicit schemes are stable on it at its 0.1 ms step.
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/paper_hanging_thread.json";
  // (Explicit Euler is unstable at this scene's 0.1 ms step: it is stepped at 1 µs, below.)
  for (const char* type : {"SymplecticEuler", "RungeKutta4", "ImplicitEuler", "ImplicitMidpoint"}) {
    const long count = allocationsInSteadySteps(path, {{"type", type}}, 200, 100);
    std::printf("  paper_hanging_thread.json with %-18s %ld allocations in 100 steps\n", type, count);
    EXPECT_EQ(count, 0) << type;
  }
  nlohmann::json document = readJsonFile(path);
  document["dt"] = 1e-6;
  const std::string small_steps = std::filesystem::temp_directory_path() / "filum_hanging_thread_1us.json";
  { std::ofstream(small_steps) << document.dump(); }
  const long count = allocationsInSteadySteps(small_steps, {{"type", "ExplicitEuler"}}, 200, 100);
  std::printf("  paper_hanging_thread.json at dt = 1 us with ExplicitEuler %ld allocations in 100 steps\n", count);
  EXPECT_EQ(count, 0) << "ExplicitEuler";
}

}  // namespace
}  // namespace filum
