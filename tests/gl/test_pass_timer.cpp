// gl::PassTimer: nested scopes on both backends. The timestamp-query path is forced on llvmpipe
// (which has ARB_timer_query) to check what the driver cannot get wrong even when its values are
// not trustworthy: no GL error, every frame's results arrive within kFrameSlots frames without
// glFinish (the ring's guarantee: frame f's query set is waited for when frame f + kFrameSlots
// begins), and each child's [begin, end] lies inside its parent's.
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <vector>

#include "gl/api/debug.h"
#include "gl/api/objects.h"
#include "gl/api/render_target.h"
#include "gl/api/timer.h"
#include "gl_test_context.h"

using namespace vplgi;

namespace {

constexpr int kSize = 64; // [px] the work target; small, llvmpipe is slow

// The scope tree each test frame opens, in opening order: {path, depth}.
const std::vector<std::pair<std::string, int>> kExpectedScopes = {
    {"frame", 0}, {"frame / clear and draw", 1}, {"frame / clear and draw / draw", 2}, {"frame / compute", 1},
    {"after", 0},
};

struct WorkTargets {
    gl::RenderTarget target{"pass timer test", gl::RenderTargetDesc::colors({GL_RGBA8})};
    gl::VertexArray noVertices{"pass timer test (no vertices)"};
    gl::Program fill;
    gl::Program compute;

    WorkTargets()
    {
        target.resize(kSize, kSize);
        const gl::ShaderLoader& shaders = test::shaders();
        fill = shaders.load("pass timer test fill", {{GL_VERTEX_SHADER, "lib/fullscreen.vert"},
                                                     {GL_FRAGMENT_SHADER, "../tests/gl/glsl/pass_timer_fill.frag"}});
        compute =
            shaders.load("pass timer test compute", {{GL_COMPUTE_SHADER, "../tests/gl/glsl/pass_timer_work.comp"}});
    }
};

// One frame of nested scopes around real GL work; never calls glFinish itself. Like the renderer,
// it binds its framebuffer inside the frame and leaves framebuffer 0 bound at the end, so
// timestamps are taken under both bindings.
void recordFrame(gl::PassTimer& timer, const WorkTargets& work, int frame)
{
    timer.beginFrame();
    {
        gl::PassTimer::Scope scope(timer, "frame");
        {
            gl::PassTimer::Scope child(timer, "clear and draw");
            glBindFramebuffer(GL_FRAMEBUFFER, work.target.framebuffer().id()); // the surfaceless context has no default one
            const float clear[4] = {0.1f * static_cast<float>(frame), 0.0f, 0.0f, 1.0f};
            glClearNamedFramebufferfv(work.target.framebuffer().id(), GL_COLOR, 0, clear);
            {
                gl::PassTimer::Scope grandchild(timer, "draw");
                glViewport(0, 0, kSize, kSize);
                glUseProgram(work.fill.id());
                glBindVertexArray(work.noVertices.id());
                glDrawArrays(GL_TRIANGLES, 0, 3);
            }
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        {
            gl::PassTimer::Scope child(timer, "compute");
            glUseProgram(work.compute.id());
            glBindImageTexture(0, work.target.color(0).id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            glDispatchCompute(kSize / 8, kSize / 8, 1);
            glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);
        }
    }
    {
        gl::PassTimer::Scope scope(timer, "after");
        const float clear[4] = {0.0f, 0.0f, 0.5f, 1.0f};
        glClearNamedFramebufferfv(work.target.framebuffer().id(), GL_COLOR, 0, clear);
    }
    timer.endFrame();
}

void checkStructure(const gl::FrameTimes& f)
{
    REQUIRE(f.passes.size() == kExpectedScopes.size());
    for (std::size_t i = 0; i < kExpectedScopes.size(); ++i) {
        CHECK(f.passes[i].path == kExpectedScopes[i].first);
        CHECK(f.passes[i].depth == kExpectedScopes[i].second);
    }
}

// The parent of nested scope i is the nearest earlier scope one level up (scopes are in opening
// order, and the first one is at depth 0).
std::size_t parentOf(const std::vector<gl::PassTime>& passes, std::size_t i)
{
    std::size_t p = i - 1;
    while (passes[p].depth != passes[i].depth - 1)
        --p;
    return p;
}

void checkNoGLError()
{
    CHECK(glGetError() == GL_NO_ERROR);
    gl::checkDebugMessages(); // throws on any KHR_debug error or high-severity message
}

} // namespace

TEST_CASE("pass timer: timestamp queries nest and arrive within kFrameSlots frames without glFinish", "[gl]")
{
    test::ensureGLContext();
    GLint counterBits = 0;
    glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &counterBits);
    REQUIRE(counterBits > 0); // the driver has timestamps (llvmpipe: 64 bits)
    WorkTargets work;
    checkNoGLError();
    const int errorsBefore = gl::highSeverityMessageCount();

    gl::PassTimer timer(gl::PassTimer::Mode::TimestampQueries);
    REQUIRE(timer.mode() == gl::PassTimer::Mode::TimestampQueries);

    constexpr int kFrames = 6;               // frames whose arrival is checked
    constexpr int kMaxLag = gl::PassTimer::kFrameSlots; // frames: what beginFrame() guarantees
    std::map<std::int64_t, int> publishedAt; // frame -> loop frame at whose beginFrame it was published
    std::vector<gl::FrameTimes> frames;
    // kMaxLag more frames after the checked ones, so each checked frame gets its kMaxLag chances.
    for (int frame = 0; frame < kFrames + kMaxLag; ++frame) {
        recordFrame(timer, work, frame); // beginFrame() inside polls the earlier frames
        for (gl::FrameTimes& f : timer.takeCompletedFrames()) {
            publishedAt[f.frame] = frame;
            // times() is the newest complete frame and never the one being recorded.
            CHECK(f.frame < frame);
            frames.push_back(std::move(f));
        }
        CHECK(timer.timesFrame() < frame);
        checkNoGLError();
    }
    for (std::int64_t f = 0; f < kFrames; ++f) {
        INFO("frame " << f);
        REQUIRE(publishedAt.count(f) == 1);
        CHECK(publishedAt[f] - f <= kMaxLag);
    }
    WARN("published frame lags: " << [&] {
        std::string s;
        for (const auto& [f, at] : publishedAt)
            s += std::to_string(at - f) + " ";
        return s;
    }());

    timer.resolve(true); // flushes the frames still in flight (waiting is allowed here)
    for (gl::FrameTimes& f : timer.takeCompletedFrames())
        frames.push_back(std::move(f));
    REQUIRE(frames.size() == static_cast<std::size_t>(kFrames + kMaxLag));
    CHECK(timer.timesFrame() == kFrames + kMaxLag - 1);

    for (std::size_t k = 0; k < frames.size(); ++k) {
        const gl::FrameTimes& f = frames[k];
        INFO("frame " << f.frame);
        CHECK(f.frame == static_cast<std::int64_t>(k)); // published in order, none lost
        checkStructure(f);
        for (std::size_t i = 0; i < f.passes.size(); ++i) {
            const gl::PassTime& t = f.passes[i];
            INFO(t.path << " [" << t.beginNs << ", " << t.endNs << "] ns");
            CHECK(t.beginNs > 0);
            CHECK(t.beginNs <= t.endNs);
            if (t.depth == 0) continue;
            const gl::PassTime& parent = f.passes[parentOf(f.passes, i)];
            INFO("parent " << parent.path << " [" << parent.beginNs << ", " << parent.endNs << "] ns");
            CHECK(parent.beginNs <= t.beginNs);
            CHECK(t.endNs <= parent.endNs);
        }
        // Siblings do not overlap: "clear and draw" ends before "compute" begins.
        CHECK(f.passes[1].endNs <= f.passes[3].beginNs);
        CHECK(f.passes[0].endNs <= f.passes[4].beginNs);
        CHECK(f.total() == f.passes[0].milliseconds + f.passes[4].milliseconds);
    }
    checkNoGLError();
    CHECK(gl::highSeverityMessageCount() == errorsBefore);
}

TEST_CASE("pass timer: glFinish + wall clock nests and total() counts top-level scopes only", "[gl]")
{
    test::ensureGLContext();
    WorkTargets work;
    gl::PassTimer timer(gl::PassTimer::Mode::FinishAndWallClock);
    for (int frame = 0; frame < 3; ++frame) {
        recordFrame(timer, work, frame);
        // As before the rewrite: the frame just rendered is complete at once.
        CHECK(timer.timesFrame() == frame);
        const std::vector<gl::FrameTimes> taken = timer.takeCompletedFrames();
        REQUIRE(taken.size() == 1);
        CHECK(taken[0].frame == frame);
        const std::vector<gl::PassTime>& times = timer.times();
        checkStructure(gl::FrameTimes{frame, times});
        for (std::size_t i = 0; i < times.size(); ++i) {
            INFO(times[i].path);
            // Each scope's own glFinish + clock reads take some time; a zero would hide double counting below.
            REQUIRE(times[i].milliseconds > 0.0);
            CHECK(times[i].beginNs == 0); // no GPU timestamps on this path
            if (times[i].depth > 0) CHECK(times[i].milliseconds <= times[parentOf(times, i)].milliseconds);
        }
        CHECK(timer.total() == times[0].milliseconds + times[4].milliseconds);
        double all = 0.0;
        for (const gl::PassTime& t : times)
            all += t.milliseconds;
        CHECK(timer.total() < all);
        checkNoGLError();
    }
}
