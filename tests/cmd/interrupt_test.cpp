// Nothing lost to Ctrl-C: the real pbrt_ext command is spawned on a white furnace
// (data/interrupt/furnace.pbrt, every pixel's expected value 0.5) with far more samples than it can
// finish, sent SIGINT once its stderr says the render runs, and its image, metadata, exit status
// and directory checked. Also the library's side: RenderOptions::cancel, and the removal of a
// temporary file by a signal handler.
#include "tests/support/scenes.h"

#include "pbrt_ext/film/film.h"
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/cmd/interrupt.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/util/atomicfile.h"

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

extern char **environ;

using namespace pbrt;

namespace {

namespace fs = std::filesystem;

const std::string kFurnace = std::string(PBRT_EXT_TEST_DATA_DIR) + "/interrupt/furnace.pbrt";
constexpr int kFurnaceSpp = 1 << 20;   // its sampler's count
constexpr double kFurnaceValue = 0.5;  // reflectance 0.5 times environment 1
// Float rounding along a path, where the estimator has no variance (seen: 2.2e-5).
constexpr double kFloatTolerance = 1e-4;

// The furnace through the film. Transport is spectral: with the mis strategy a sample's radiance
// is exactly 0.5 L(lambda) at each of its four wavelengths (L: the white "rgb L [1 1 1]", D65 at
// 1 nit; the reflectance 0.5 is the constant spectrum of a gray), but the RGB the film records
// for it depends on the wavelengths it carries, SampledWavelengths::SampleVisible(u) for the
// sample's first dimension u. Over u that RGB averages to exactly kFurnaceValue per channel (the
// sensor's estimate is unbiased and sRGB's white is D65) and stays within [min, max]; so does
// every pixel, an average of such samples, while a pixel without samples is 0.
struct FurnaceSamples {
    RGB min, max;
    RGB secondMoment;  // the mean over u of the square
};
const FurnaceSamples &FurnaceSampleRGB() {
    static const FurnaceSamples samples = [] {
        const RGBColorSpace &cs = RGBColorSpace::sRGB();
        Spectrum Le = RGBIlluminantSpectrum(cs, RGB(1, 1, 1));
        Float scale = 1 / SpectrumToPhotometric(Le);  // as CreateLight makes it
        Spectrum R = RGBAlbedoSpectrum(cs, RGB(0.5f, 0.5f, 0.5f));
        PixelSensor sensor = PixelSensor::CreateDefault();  // the film's: cie1931, sRGB output
        FurnaceSamples s{RGB(Infinity, Infinity, Infinity), RGB(-Infinity, -Infinity, -Infinity),
                         RGB(0, 0, 0)};
        // Midpoints of 2^20 intervals of u: between them the RGB moves by less than 1e-5.
        constexpr int n = 1 << 20;
        for (int i = 0; i < n; ++i) {
            SampledWavelengths lambda = SampledWavelengths::SampleVisible((i + 0.5f) / n);
            SampledSpectrum L = scale * Le.Sample(lambda) * R.Sample(lambda);
            RGB rgb = cs.ToRGB(Mul<XYZ>(sensor.XYZFromSensorRGB, sensor.ToSensorRGB(L, lambda)));
            for (int c = 0; c < 3; ++c) {
                s.min[c] = std::min(s.min[c], rgb[c]);
                s.max[c] = std::max(s.max[c], rgb[c]);
                s.secondMoment[c] += Sqr(rgb[c]) / n;
            }
        }
        return s;
    }();
    return samples;
}

// The light strategy's standard deviation per sample of the red channel. The direction gives
// 4 cos(theta)+ for a direction uniform on the sphere (mean 1, second moment 8/3) and the
// wavelengths, independently, the film's RGB V of 0.5 L (mean 0.5, second moment E[V^2] above):
// the product has mean 0.5 and second moment 8/3 E[V^2]. (Before spectral transport V was
// exactly 0.5, and this was sqrt(5/3) 0.5 = 0.645; now it is about 0.657.)
double LightSampleSigma() {
    return std::sqrt(8.0 / 3.0 * FurnaceSampleRGB().secondMoment[0] - Sqr(kFurnaceValue));
}
// Generous: under AddressSanitizer on a loaded machine the command is several times slower, and
// a wait ends as soon as its event comes.
constexpr double kTimeoutSeconds = 120;
// The command's stderr when it starts rendering (from then on SIGINT stops the render) and when
// it has taken the first SIGINT.
constexpr const char *kRenderStarted = "pbrt_ext: rendering ";
constexpr const char *kFirstInterruptTaken = "interrupt again, a second later, to quit without writing";
// The progress bar's first redraw (250 ms into the render).
constexpr const char *kProgressDrawn = "Rendering [";

// The pbrt_ext command running in the background, its stderr read through a pipe. The
// destructor kills it if a failed check left it running.
class RunningCli {
  public:
    explicit RunningCli(const std::vector<std::string> &args) {
        int fds[2];
        if (::pipe2(fds, O_CLOEXEC) != 0)
            throw std::system_error(errno, std::generic_category(), "pipe2");
        stderrFd = fds[0];
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
        // Whatever the test runner blocks or ignores, the command gets SIGINT's defaults.
        posix_spawnattr_t attr;
        posix_spawnattr_init(&attr);
        sigset_t none, sigint;
        sigemptyset(&none);
        sigemptyset(&sigint);
        sigaddset(&sigint, SIGINT);
        posix_spawnattr_setsigmask(&attr, &none);
        posix_spawnattr_setsigdefault(&attr, &sigint);
        posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
        std::vector<char *> argv{const_cast<char *>(PBRT_EXT_CLI)};
        for (const std::string &a : args)
            argv.push_back(const_cast<char *>(a.c_str()));
        argv.push_back(nullptr);
        int error = posix_spawn(&pid, PBRT_EXT_CLI, &actions, &attr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        posix_spawnattr_destroy(&attr);
        ::close(fds[1]);
        if (error != 0)
            throw std::system_error(error, std::generic_category(), "posix_spawn " PBRT_EXT_CLI);
    }
    ~RunningCli() {
        if (!status) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, nullptr, 0);
        }
        ::close(stderrFd);
    }
    RunningCli(const RunningCli &) = delete;
    RunningCli &operator=(const RunningCli &) = delete;

    void Interrupt() const { ::kill(pid, SIGINT); }

    // Reads stderr until it holds text; false if the command closed it (exited) or the timeout
    // passed first.
    bool WaitForOutput(const std::string &text) {
        auto deadline = Clock::now() + std::chrono::duration<double>(kTimeoutSeconds);
        while (output.find(text) == std::string::npos)
            if (Clock::now() > deadline || !ReadSome(100))
                return false;
        return true;
    }

    // The wait status once the command has exited, reading its stderr to the end meanwhile (so
    // that it never blocks on a full pipe); empty after the timeout.
    std::optional<int> WaitForExit() {
        auto deadline = Clock::now() + std::chrono::duration<double>(kTimeoutSeconds);
        while (Clock::now() < deadline)
            if (!ReadSome(100)) {  // end of file: the command is gone or going
                int s = 0;
                if (::waitpid(pid, &s, 0) == pid)
                    status = s;
                return status;
            }
        return {};
    }

    const std::string &Output() const { return output; }

  private:
    using Clock = std::chrono::steady_clock;

    // Appends what arrives within timeoutMs; false at end of file.
    bool ReadSome(int timeoutMs) {
        pollfd p{stderrFd, POLLIN, 0};
        if (::poll(&p, 1, timeoutMs) <= 0)
            return true;
        char buffer[4096];
        ssize_t n = ::read(stderrFd, buffer, sizeof(buffer));
        if (n > 0)
            output.append(buffer, size_t(n));
        return n > 0 || (n < 0 && errno == EINTR);
    }

    pid_t pid = -1;
    int stderrFd = -1;
    std::string output;
    std::optional<int> status;
};

// A fresh directory per test, removed afterwards.
class InterruptCli : public ::testing::Test {
  protected:
    void SetUp() override {
        char pattern[] = "/tmp/pbrt_ext_interrupt_XXXXXX";
        ASSERT_NE(::mkdtemp(pattern), nullptr);
        dir = pattern;
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir, ignored);
    }
    std::string Output() const { return dir + "/furnace.exr"; }
    std::vector<std::string> FilesInDir() const {
        std::vector<std::string> names;
        for (const fs::directory_entry &e : fs::directory_iterator(dir))
            names.push_back(e.path().filename().string());
        return names;
    }

    std::string dir;
};

void ExpectInterruptedExit(std::optional<int> status, const std::string &output) {
    ASSERT_TRUE(status) << "still running after " << kTimeoutSeconds << " s\n" << output;
    ASSERT_TRUE(WIFEXITED(*status)) << "ended by signal " << WTERMSIG(*status) << "\n" << output;
    EXPECT_EQ(WEXITSTATUS(*status), 130) << output;
}

// "pbrt_ext: interrupted: wrote FILE: N of S samples per pixel (M in part of the image) in T s",
// the parenthesis only where M > N.
struct InterruptedMessage {
    int samplesPerPixel = 0, maxSamplesPerPixel = 0;
    std::string file;
};

std::optional<InterruptedMessage> ParseInterruptedMessage(const std::string &output) {
    size_t at = output.find("pbrt_ext: interrupted: wrote ");
    if (at == std::string::npos)
        return {};
    const char *line = output.c_str() + at;
    InterruptedMessage m;
    char file[4096];
    int asked = 0, consumed = 0;
    if (std::sscanf(line, "pbrt_ext: interrupted: wrote %4095[^:]: %d of %d samples per pixel%n",
                    file, &m.samplesPerPixel, &asked, &consumed) != 3)
        return {};
    m.file = file;
    m.maxSamplesPerPixel = m.samplesPerPixel;
    std::sscanf(line + consumed, " (%d in part of the image)", &m.maxSamplesPerPixel);
    return m;
}

int IntAttribute(const Imf::Header &header, const char *name) {
    const Imf::IntAttribute *a = header.findTypedAttribute<Imf::IntAttribute>(name);
    return a ? a->value() : -1;
}

}  // namespace

TEST_F(InterruptCli, FirstSigintWritesTheSamplesSoFarWithTheirCount) {
    // The light strategy gives every sample variance, so the image mean tests the weighting of
    // samples in an image whose tiles may hold different counts. 32 x 32 pixels make quick waves.
    RunningCli cli({"--nthreads", "2", "--strategy", "light", "--pixelbounds", "0,32,0,32",
                    "--outfile", Output(), kFurnace});
    ASSERT_TRUE(cli.WaitForOutput(kRenderStarted)) << cli.Output();
    // Some waves in: the render is well under way, and the first wave is done.
    ASSERT_TRUE(cli.WaitForOutput(kProgressDrawn)) << cli.Output();
    cli.Interrupt();
    ExpectInterruptedExit(cli.WaitForExit(), cli.Output());
    // Renamed into place: no temporary file beside it.
    EXPECT_EQ(FilesInDir(), std::vector<std::string>{"furnace.exr"});

    Imf::InputFile file(Output().c_str());
    const Imf::Header &header = file.header();
    const int spp = IntAttribute(header, "samplesPerPixel");
    const int maxSpp = IntAttribute(header, "maxSamplesPerPixel");
    EXPECT_EQ(IntAttribute(header, "interrupted"), 1);
    ASSERT_GE(spp, 1);
    ASSERT_LT(maxSpp, kFurnaceSpp);
    // A tile stops between waves, and waves hold at most 64 samples.
    EXPECT_GE(maxSpp, spp);
    EXPECT_LE(maxSpp - spp, 64);
    std::optional<InterruptedMessage> said = ParseInterruptedMessage(cli.Output());
    ASSERT_TRUE(said) << cli.Output();
    EXPECT_EQ(said->samplesPerPixel, spp);
    EXPECT_EQ(said->maxSamplesPerPixel, maxSpp);
    EXPECT_EQ(said->file, Output());

    // Every pixel is the mean of at least spp samples, each within [0, 4 * max V] (V: the
    // film's red for the sample's wavelengths, FurnaceSampleRGB). The image mean of n pixels has
    // a standard error of at most sigma / sqrt(n spp); 4 of them is the threshold (fixed seed; a
    // correct render fails 6e-5 of the time).
    Image image = Image::Read(Output());
    ASSERT_EQ(image.Resolution(), Point2i(32, 32));
    double sum = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            Float v = image.GetChannel(Point2i(x, y), 0);
            ASSERT_TRUE(std::isfinite(v)) << x << ", " << y;
            ASSERT_GE(v, 0) << x << ", " << y;
            ASSERT_LE(v, 4 * FurnaceSampleRGB().max[0] + 1e-5) << x << ", " << y;
            sum += v;
        }
    double standardError = LightSampleSigma() / std::sqrt(32.0 * 32.0 * spp);
    EXPECT_NEAR(sum / (32 * 32), kFurnaceValue, 4 * standardError)
        << spp << " to " << maxSpp << " samples per pixel";
}

TEST_F(InterruptCli, TwoSigintsTogetherAreOneInterrupt) {
    // As `timeout -s INT` and a shell's job control deliver it: to the process and its group.
    RunningCli cli({"--nthreads", "2", "--pixelbounds", "0,32,0,32", "--outfile", Output(), kFurnace});
    ASSERT_TRUE(cli.WaitForOutput(kProgressDrawn)) << cli.Output();
    cli.Interrupt();
    cli.Interrupt();
    ExpectInterruptedExit(cli.WaitForExit(), cli.Output());
    EXPECT_EQ(cli.Output().find("quitting without writing"), std::string::npos) << cli.Output();
    EXPECT_TRUE(ParseInterruptedMessage(cli.Output())) << cli.Output();
    EXPECT_EQ(FilesInDir(), std::vector<std::string>{"furnace.exr"});
}

TEST_F(InterruptCli, ADeliberateSecondSigintQuitsAtOnceWithoutWriting) {
    // The first SIGINT comes in the first wave, which completes before the render stops: 16.7
    // million pixels on one thread take seconds, time for a second Ctrl-C well after the first.
    RunningCli cli({"--nthreads", "1", "--resolution", "4096,4096", "--outfile", Output(), kFurnace});
    ASSERT_TRUE(cli.WaitForOutput(kRenderStarted)) << cli.Output();
    cli.Interrupt();
    ASSERT_TRUE(cli.WaitForOutput(kFirstInterruptTaken)) << cli.Output();
    std::this_thread::sleep_for(std::chrono::nanoseconds(kSameInterruptNanoseconds) +
                                std::chrono::milliseconds(200));
    cli.Interrupt();
    ExpectInterruptedExit(cli.WaitForExit(), cli.Output());
    EXPECT_NE(cli.Output().find("quitting without writing the image"), std::string::npos)
        << cli.Output();
    EXPECT_EQ(FilesInDir(), std::vector<std::string>{});  // no image, no temporary file
}

TEST_F(InterruptCli, SigintInTheFirstWaveStillSamplesEveryPixel) {
    // As soon as the render starts: typically within the first wave over these 65536 pixels
    // (tens of milliseconds), and the checks hold wherever it lands. The first wave always
    // completes (see RenderOptions::cancel), so every pixel has a sample: with the mis strategy
    // every sample lies within FurnaceSampleRGB's range (about [0.38, 0.63] in red, [0.47, 0.53]
    // in green, [0.10, 0.91] in blue; it was exactly 0.5 before spectral transport), and an
    // unsampled pixel is 0.
    RunningCli cli({"--nthreads", "2", "--pixelbounds", "0,256,0,256", "--outfile",
                    Output(), kFurnace});
    ASSERT_TRUE(cli.WaitForOutput(kRenderStarted)) << cli.Output();
    cli.Interrupt();
    ExpectInterruptedExit(cli.WaitForExit(), cli.Output());
    EXPECT_EQ(FilesInDir(), std::vector<std::string>{"furnace.exr"});

    Imf::InputFile file(Output().c_str());
    EXPECT_EQ(IntAttribute(file.header(), "interrupted"), 1);
    EXPECT_GE(IntAttribute(file.header(), "samplesPerPixel"), 1);
    Image image = Image::Read(Output());
    ASSERT_EQ(image.Resolution(), Point2i(256, 256));
    const FurnaceSamples &range = FurnaceSampleRGB();
    for (int c = 0; c < 3; ++c)
        ASSERT_GT(range.min[c], 0.05) << c;  // so that the check below tells a sample from none
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            for (int c = 0; c < 3; ++c) {
                Float v = image.GetChannel(Point2i(x, y), c);
                ASSERT_GE(v, range.min[c] - kFloatTolerance) << x << ", " << y << " channel " << c;
                ASSERT_LE(v, range.max[c] + kFloatTolerance) << x << ", " << y << " channel " << c;
            }
}

TEST(RenderCancel, BeforeTheFirstWaveEndsTheImageIsTheOneSampleImage) {
    // Cancelled from the start, the render still completes the first wave and nothing more: the
    // same image as a render of one sample per pixel, with the counts saying so.
    // The independent sampler's samples do not depend on the count asked; the light strategy
    // makes every sample differ.
    auto scene = [](int spp) {
        using namespace testscenes;
        SceneBuilder builder(LookingAt(Point3f(0, 0, 5), Point3f(0, 0, 0), 30, Point2i(40, 24)),
                             BoxFilteredFilm(Point2i(40, 24)), IndependentSampler(spp, 3));
        builder.AddSphere(UnitSphereAt(Point3f(0, 0, 0)),
                          builder.AddMaterial(DiffuseMaterial{Spectrum(0.5f)}));
        builder.AddLight(UniformInfiniteLight(Spectrum(1.f), 1));
        builder.SetIntegrator(PathTracer(1, PathStrategy::Light));
        return builder.Build();
    };
    std::atomic<bool> cancel{true};
    auto cancelled = scene(64);
    RenderOptions options{2, true};
    options.cancel = &cancel;
    RenderStatistics stats = Render(*cancelled, options);
    EXPECT_TRUE(stats.cancelled);
    EXPECT_EQ(stats.samplesPerPixel, 1);
    EXPECT_EQ(stats.maxSamplesPerPixel, 1);
    EXPECT_EQ(stats.cameraSamples, 40 * 24);
    auto oneSample = scene(1);
    Render(*oneSample, {2, true});
    for (Point2i p : oneSample->film.PixelBounds())
        ASSERT_EQ(cancelled->film.GetPixelRGB(p), oneSample->film.GetPixelRGB(p))
            << p.x << ", " << p.y;
}

namespace {
// Plays the part of the command's SIGINT handler in the next test.
void RemoveUnfinishedFilesOnSignal(int) { RemoveUnfinishedFiles(); }
}  // namespace

TEST(InterruptCleanup, SignalHandlerRemovesTheTemporaryFileOfAWriteInProgress) {
    // The second SIGINT may come while an image is being written: the handler then removes the
    // temporary file before exiting. Here it returns instead, so the write goes on, finds its
    // file gone, and fails without creating the target.
    char pattern[] = "/tmp/pbrt_ext_cleanup_XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    const fs::path dir = pattern, target = dir / "image.exr";
    struct sigaction action = {}, previous = {};
    action.sa_handler = RemoveUnfinishedFilesOnSignal;
    sigemptyset(&action.sa_mask);
    ASSERT_EQ(::sigaction(SIGUSR1, &action, &previous), 0);
    std::string tmpPath;
    EXPECT_THROW(WriteFileAtomically(target.string(),
                                     [&](const std::string &tmp) {
                                         tmpPath = tmp;
                                         std::ofstream(tmp) << "half an image";
                                         ASSERT_TRUE(fs::exists(tmp));
                                         ::raise(SIGUSR1);
                                         EXPECT_FALSE(fs::exists(tmp));
                                     }),
                 std::runtime_error);
    ::sigaction(SIGUSR1, &previous, nullptr);
    EXPECT_EQ(fs::path(tmpPath).parent_path(), dir);  // beside the target, as documented
    EXPECT_TRUE(fs::is_empty(dir));
    fs::remove_all(dir);
}
