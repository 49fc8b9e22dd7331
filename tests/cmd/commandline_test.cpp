// pbrt-v4's command line: the parser (cmd/commandline.h) on pbrt-v4's syntax, and the pbrt_ext
// command itself, spawned, for its exit statuses, messages, output-file check, standard input and
// several scene files.
#include "pbrt_ext/cmd/commandline.h"
#include "pbrt_ext/images/image.h"

#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace pbrt;

namespace {

namespace fs = std::filesystem;

CommandLine Parse(std::vector<std::string> args) { return ParseCommandLine(args); }

std::string ErrorOf(std::vector<std::string> args) {
    try {
        ParseCommandLine(args);
    } catch (const CommandLineError &e) {
        return e.what();
    }
    return "";
}

TEST(CommandLine, CommaListsAsPbrtV4) {
    CommandLine c = Parse({"--cropwindow", "0,0.5,0.25,1", "--pixelbounds=1,20,3,40", "s.pbrt"});
    EXPECT_EQ(c.overrides.cropWindow, Bounds2f(Point2f(0, 0.25f), Point2f(0.5f, 1)));
    EXPECT_EQ(c.overrides.pixelBounds, Bounds2i(Point2i(1, 3), Point2i(20, 40)));
    EXPECT_EQ(c.sceneFiles, std::vector<std::string>{"s.pbrt"});
    c = Parse({"--pixel", "7,9"});
    EXPECT_EQ(c.overrides.pixelBounds, Bounds2i(Point2i(7, 9), Point2i(8, 10)));
    c = Parse({"--resolution", "64,48"});
    EXPECT_EQ(c.overrides.resolution, Point2i(64, 48));
    // The same numbers with spaces, as pbrt_ext took them before.
    c = Parse({"--resolution", "64", "48", "--cropwindow", "0", "0.5", "0.25", "1", "s.pbrt"});
    EXPECT_EQ(c.overrides.resolution, Point2i(64, 48));
    EXPECT_EQ(c.overrides.cropWindow, Bounds2f(Point2f(0, 0.25f), Point2f(0.5f, 1)));
    EXPECT_EQ(c.sceneFiles, std::vector<std::string>{"s.pbrt"});
}

TEST(CommandLine, NamesAsPbrtV4MatchesThem) {
    // One or two dashes, "=value", and names ignoring case, '-' and '_'.
    CommandLine c = Parse({"-spp", "8", "--NThreads=3", "--disable_pixel_jitter", "--quiet=false"});
    EXPECT_EQ(c.overrides.spp, 8);
    EXPECT_EQ(c.overrides.nThreads, 3);
    EXPECT_TRUE(c.overrides.disablePixelJitter);
    EXPECT_FALSE(c.overrides.quiet);
}

TEST(CommandLine, TheLastOfARepeatedOptionWins) {
    CommandLine c = Parse({"--spp", "4", "--quiet", "--spp", "16", "--quiet=false", "a.pbrt", "b.pbrt"});
    EXPECT_EQ(c.overrides.spp, 16);
    EXPECT_FALSE(c.overrides.quiet);
    EXPECT_EQ(c.sceneFiles, (std::vector<std::string>{"a.pbrt", "b.pbrt"}));
}

TEST(CommandLine, EveryPbrtV4SwitchSetsItsOverride) {
    CommandLine c = Parse({"--quick", "--force-diffuse", "--disable-wavelength-jitter",
                           "--disable-texture-filtering", "--disable-image-textures", "--stats",
                           "--seed", "-3", "--outfile", "x.pfm", "--displacement-edge-scale", "2",
                           "--render-coord-sys", "world", "--log-level", "verbose", "--log-file", "l.txt"});
    const RenderOverrides &o = c.overrides;
    EXPECT_TRUE(o.quick && o.forceDiffuse && o.disableWavelengthJitter &&
                o.disableTextureFiltering && o.disableImageTextures && o.stats);
    EXPECT_EQ(o.seed, -3);
    EXPECT_EQ(o.outFile, "x.pfm");
    EXPECT_EQ(o.displacementEdgeScale, 2);
    EXPECT_EQ(c.logLevel, LogLevel::Verbose);
    EXPECT_EQ(c.logFile, "l.txt");
}

TEST(CommandLine, WavefrontRendersWithVolpath) {
    EXPECT_EQ(Parse({"--wavefront"}).overrides.integrator, "volpath");
    // An explicit integrator wins, wherever it is.
    EXPECT_EQ(Parse({"--integrator", "bdpt", "--wavefront"}).overrides.integrator, "bdpt");
}

TEST(CommandLine, StandardInputIsADash) {
    EXPECT_EQ(Parse({"-", "--spp", "1"}).sceneFiles, std::vector<std::string>{"-"});
}

TEST(CommandLine, BadValuesSayWhatIsExpected) {
    EXPECT_NE(ErrorOf({"--cropwindow", "0,0.5,0"}).find("expected 4 comma-separated values"), std::string::npos);
    EXPECT_NE(ErrorOf({"--cropwindow", "0 1 0 1"}).find("--cropwindow"), std::string::npos);
    EXPECT_NE(ErrorOf({"--spp", "0"}).find("less than 1"), std::string::npos);
    EXPECT_NE(ErrorOf({"--spp", "-5"}).find("less than 1"), std::string::npos);
    EXPECT_NE(ErrorOf({"--spp", "4x"}).find("not an integer"), std::string::npos);
    EXPECT_NE(ErrorOf({"--spp"}).find("expected a value"), std::string::npos);
    EXPECT_NE(ErrorOf({"--quiet=maybe"}).find("true or false"), std::string::npos);
    EXPECT_NE(ErrorOf({"--log-level", "loud"}).find("verbose, error or fatal"), std::string::npos);
    EXPECT_NE(ErrorOf({"--integrator", "pathh"}).find("--integrator"), std::string::npos);
    EXPECT_NE(ErrorOf({"--render-coord-sys", "screen"}).find("camera, cameraworld or world"), std::string::npos);
}

TEST(CommandLine, AnUnknownOptionSuggestsTheNearest) {
    EXPECT_NE(ErrorOf({"--sp", "4", "scene.pbrt"}).find("unknown option --sp; did you mean --spp?"),
              std::string::npos);
    EXPECT_NE(ErrorOf({"--cropwindw", "0,1,0,1"}).find("did you mean --cropwindow?"), std::string::npos);
    EXPECT_NE(ErrorOf({"--outfil", "x.exr"}).find("did you mean --outfile?"), std::string::npos);
    // Nothing near: no suggestion.
    std::string far = ErrorOf({"--zzzzzzzzzzzz"});
    EXPECT_NE(far.find("unknown option"), std::string::npos);
    EXPECT_EQ(far.find("did you mean"), std::string::npos);
}

TEST(CommandLine, MSEReferenceAndOutputGoTogether) {
    EXPECT_NE(ErrorOf({"--mse-reference-image", "ref.exr"}).find("go together"), std::string::npos);
    CommandLine c = Parse({"--mse-reference-image", "ref.exr", "--mse-reference-out", "mse.txt",
                           "--write-partial-images", "--display-server", "localhost:14158"});
    EXPECT_EQ(c.overrides.mseReferenceImage, "ref.exr");
    EXPECT_EQ(c.overrides.mseReferenceOut, "mse.txt");
    EXPECT_TRUE(c.writePartialImages);
    EXPECT_EQ(c.displayServer, "localhost:14158");
}

TEST(CommandLine, GpuOptionsAreRefusedWithTheReason) {
    EXPECT_NE(ErrorOf({"--gpu"}).find("renders on the CPU"), std::string::npos);
    EXPECT_NE(ErrorOf({"--interactive"}).find("not supported"), std::string::npos);
}

TEST(CommandLine, HelpGroupsPbrtV4sOptionsThenOursAndShowsMerge) {
    std::string help = CommandLineHelp();
    size_t v4 = help.find("pbrt-v4's options:"), ours = help.find("pbrt_ext's own options:");
    ASSERT_NE(v4, std::string::npos);
    ASSERT_NE(ours, std::string::npos);
    EXPECT_LT(v4, ours);
    EXPECT_LT(help.find("--cropwindow <x0,x1,y0,y1>"), ours);
    EXPECT_GT(help.find("--integrator <name>"), ours);
    EXPECT_NE(help.find("pbrt_ext merge"), std::string::npos);
    EXPECT_NE(help.find("130 interrupted"), std::string::npos);
}

// ---- The command ------------------------------------------------------------------------------

struct Result {
    int status = -1;
    std::string output;  // standard output and error together
};

// Runs the command through the shell (stdin, redirections), in dir.
Result Command(const std::string &args, const fs::path &dir) {
    std::string line = "cd '" + dir.string() + "' && '" + std::string(PBRT_EXT_CLI) + "' " + args + " 2>&1";
    Result run;
    std::FILE *pipe = ::popen(line.c_str(), "r");
    if (!pipe) return run;
    char buffer[4096];
    while (size_t n = std::fread(buffer, 1, sizeof(buffer), pipe)) run.output.append(buffer, n);
    int status = ::pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

constexpr const char *kCamera = "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 6\n"
                                "Sampler \"independent\" \"integer pixelsamples\" 2\n"
                                "Camera \"perspective\"\n";
constexpr const char *kWorld = "WorldBegin\nLightSource \"infinite\" \"rgb L\" [1 1 1]\n"
                               "Material \"diffuse\"\nShape \"sphere\" \"float radius\" 0.5\n";

class CommandTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir = fs::temp_directory_path() /
              ("pbrt_ext_cli_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
        Write("camera.pbrt", kCamera);
        Write("world.pbrt", kWorld);
        Write("scene.pbrt", std::string(kCamera) + kWorld);
    }
    void TearDown() override { fs::remove_all(dir); }
    void Write(const std::string &name, const std::string &text) { std::ofstream(dir / name) << text; }
    fs::path dir;
};

TEST_F(CommandTest, ExitStatuses) {
    EXPECT_EQ(Command("--quiet --outfile out.exr scene.pbrt", dir).status, 0);
    EXPECT_EQ(Command("--sp 4 scene.pbrt", dir).status, 2);
    EXPECT_EQ(Command("--spp 0 scene.pbrt", dir).status, 2);
    Write("bad.pbrt", "WorldBegin\nShape \"nonsense\"\n");
    Result bad = Command("bad.pbrt", dir);
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.output.find("bad.pbrt:2:"), std::string::npos) << bad.output;
    EXPECT_EQ(Command("merge", dir).status, 2);
}

TEST_F(CommandTest, VersionAndHelpNeedNoScene) {
    Result version = Command("--version", dir);
    EXPECT_EQ(version.status, 0);
    EXPECT_EQ(version.output.rfind("pbrt_ext ", 0), 0u) << version.output;
    Result help = Command("--help", dir);
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.output.find("merge"), std::string::npos);
}

TEST_F(CommandTest, AnOutfileThatCantBeWrittenStopsBeforeTheRender) {
    for (const char *name : {"x.foo", "noextension", "/nonexistent/dir/x.exr"}) {
        Result run = Command(std::string("--outfile ") + name + " scene.pbrt", dir);
        EXPECT_EQ(run.status, 2) << name << ": " << run.output;
        EXPECT_EQ(run.output.find("rendering"), std::string::npos) << name << ": " << run.output;
        EXPECT_EQ(run.output.find(".tmp"), std::string::npos) << run.output;
    }
    // The film's own filename is checked after loading, still before rendering.
    Write("film.pbrt", std::string("Film \"rgb\" \"string filename\" \"y.foo\"\n") + kWorld);
    Result film = Command("film.pbrt", dir);
    EXPECT_EQ(film.status, 1) << film.output;
    EXPECT_NE(film.output.find("nothing rendered"), std::string::npos) << film.output;
    EXPECT_FALSE(fs::exists(dir / "y.foo"));
}

// Reads a PFM's header and pixel count; the file is the one just written.
TEST_F(CommandTest, WritesPFMAndSaysWhere) {
    Result run = Command("--outfile out.pfm scene.pbrt", dir);
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("wrote out.pfm: 2 of 2 samples per pixel"), std::string::npos) << run.output;
    std::ifstream in(dir / "out.pfm", std::ios::binary);
    std::string magic, scale;
    int w = 0, h = 0;
    in >> magic >> w >> h >> scale;
    EXPECT_EQ(magic, "PF");
    EXPECT_EQ(w, 8);
    EXPECT_EQ(h, 6);
    EXPECT_EQ(scale, "-1");
    EXPECT_EQ(fs::file_size(dir / "out.pfm"), size_t(in.tellg()) + 1 + 8 * 6 * 3 * sizeof(float));
}

TEST_F(CommandTest, SeveralFilesAndStandardInputAreOneScene) {
    Result files = Command("--outfile a.pfm camera.pbrt world.pbrt", dir);
    ASSERT_EQ(files.status, 0) << files.output;
    Result stdinFile = Command("--outfile b.pfm camera.pbrt - < world.pbrt", dir);
    ASSERT_EQ(stdinFile.status, 0) << stdinFile.output;
    Result whole = Command("--outfile c.pfm - < scene.pbrt", dir);
    ASSERT_EQ(whole.status, 0) << whole.output;
    auto bytes = [&](const char *name) {
        std::ifstream in(dir / name, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    // The same scene and seed: the same image, bit for bit.
    EXPECT_EQ(bytes("a.pfm"), bytes("c.pfm"));
    EXPECT_EQ(bytes("b.pfm"), bytes("c.pfm"));
}

TEST_F(CommandTest, AnImageErrorNamesTheSceneLineThatAskedForIt) {
    Write("cut.png", std::string("\x89PNG\r\n\x1a\n", 8));
    Write("textured.pbrt", std::string(kCamera) +
                               "WorldBegin\nLightSource \"infinite\" \"rgb L\" [1 1 1]\n"
                               "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"cut.png\"\n"
                               "Material \"diffuse\" \"texture reflectance\" \"t\"\n"
                               "Shape \"sphere\"\n");
    Result run = Command("textured.pbrt", dir);
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.output.find("textured.pbrt:6:"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("cut.png"), std::string::npos) << run.output;
}

TEST_F(CommandTest, ATimeLimitSaysItStoppedAndHowFar) {
    Write("long.pbrt", std::string("Film \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 32\n"
                                   "Sampler \"independent\" \"integer pixelsamples\" 100000000\n") + kWorld);
    Result run = Command("--time-limit 0.5 --outfile long.exr long.pbrt", dir);
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("time limit of 0.5 s: wrote long.exr:"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("of 100000000 samples per pixel"), std::string::npos) << run.output;
}

TEST_F(CommandTest, APbrtV3SceneSaysHowToUpgrade) {
    Write("v3.pbrt", "Film \"image\"\nWorldBegin\n");
    Result run = Command("v3.pbrt", dir);
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.output.find("pbrt --upgrade"), std::string::npos) << run.output;
}

// A PFM's float RGB, top row first, as the command wrote it.
std::vector<float> ReadPFM(const fs::path &path, int *width, int *height) {
    std::ifstream in(path, std::ios::binary);
    std::string magic, scale;
    in >> magic >> *width >> *height >> scale;
    in.get();
    std::vector<float> rows(3 * size_t(*width) * size_t(*height));
    in.read(reinterpret_cast<char *>(rows.data()), std::streamsize(rows.size() * sizeof(float)));
    std::vector<float> image(rows.size());
    const size_t row = 3 * size_t(*width);
    for (int y = 0; y < *height; ++y)  // the file's first row is the bottom one
        std::copy_n(rows.begin() + ptrdiff_t((*height - 1 - y) * row), row, image.begin() + ptrdiff_t(y * row));
    return image;
}

TEST_F(CommandTest, MSEAgainstAReferenceAfterEveryWave) {
    // Seen from outside the sphere: every sample's wavelengths make its noise.
    Write("big.pbrt", std::string("LookAt 0 0 3  0 0 0  0 1 0\nCamera \"perspective\"\n"
                                  "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 6\n"
                                  "Sampler \"independent\" \"integer pixelsamples\" 129\n") + kWorld);
    ASSERT_EQ(Command("--quiet --outfile ref.pfm big.pbrt", dir).status, 0);
    Result run = Command("--quiet --seed 3 --outfile out.pfm --mse-reference-image ref.pfm "
                         "--mse-reference-out mse.txt big.pbrt", dir);
    ASSERT_EQ(run.status, 0) << run.output;
    // Waves of 1, 64 and 64 samples.
    std::ifstream in(dir / "mse.txt");
    std::vector<std::pair<int, double>> rows;
    for (std::pair<int, double> r; in >> r.first >> r.second;) rows.push_back(r);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].first, 1);
    EXPECT_EQ(rows[1].first, 65);
    EXPECT_EQ(rows[2].first, 129);
    // The last row is the written image's MSE against the reference.
    int w = 0, h = 0;
    std::vector<float> out = ReadPFM(dir / "out.pfm", &w, &h), ref = ReadPFM(dir / "ref.pfm", &w, &h);
    double mse = 0;
    for (size_t i = 0; i < out.size(); ++i) mse += (double(out[i]) - ref[i]) * (double(out[i]) - ref[i]);
    mse /= double(out.size());
    EXPECT_GT(mse, 0);
    EXPECT_NEAR(rows[2].second, mse, 1e-6 * mse);
    // A reference of another size is an error before the render.
    Write("small.pbrt", std::string("Film \"rgb\" \"integer xresolution\" 4 \"integer yresolution\" 4\n") + kWorld);
    Result small = Command("--outfile s.pfm --mse-reference-image ref.pfm --mse-reference-out m.txt small.pbrt", dir);
    EXPECT_EQ(small.status, 1);
    EXPECT_NE(small.output.find("8 x 6 pixels; the render is 4 x 4"), std::string::npos) << small.output;
    EXPECT_FALSE(fs::exists(dir / "s.pfm"));
}

TEST_F(CommandTest, SceneOptionsAskForMSELinesAndPixelStatsAsTheCommandLineDoes) {
    const std::string film = "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 6\n"
                             "Sampler \"independent\" \"integer pixelsamples\" 4\n";
    Write("opts.pbrt", "Option \"string msereferenceimage\" \"ref.pfm\"\n"
                       "Option \"string msereferenceout\" \"mse.txt\"\nOption \"pixelstats\" true\n" +
                           film + kWorld);
    ASSERT_EQ(Command("--quiet --outfile ref.pfm scene.pbrt", dir).status, 0);
    Result run = Command("--quiet --outfile out.exr opts.pbrt", dir);
    ASSERT_EQ(run.status, 0) << run.output;
    std::ifstream in(dir / "mse.txt");
    int spp = 0;
    double mse = -1;
    ASSERT_TRUE(in >> spp >> mse);
    EXPECT_EQ(spp, 1);  // the first wave
    EXPECT_GE(mse, 0);
    EXPECT_TRUE(fs::exists(dir / "out-time.exr"));
    EXPECT_TRUE(fs::exists(dir / "out-rays.exr"));
    // The file wins over the command line, as in pbrt-v4.
    Write("nostats.pbrt", "Option \"pixelstats\" false\n" + film + kWorld);
    ASSERT_EQ(Command("--quiet --pixelstats --outfile off.exr nostats.pbrt", dir).status, 0);
    EXPECT_FALSE(fs::exists(dir / "off-time.exr"));
    // A reference image without the file for its lines is an error at its Option.
    Write("half.pbrt", "Option \"string msereferenceimage\" \"ref.pfm\"\n" + film + kWorld);
    Result half = Command("--quiet --outfile half.exr half.pbrt", dir);
    EXPECT_EQ(half.status, 1);
    EXPECT_NE(half.output.find("half.pbrt:1:1: error: option \"msereferenceimage\" needs "
                               "\"msereferenceout\" too"), std::string::npos) << half.output;
    EXPECT_FALSE(fs::exists(dir / "half.exr"));
    // With both on the command line, the file's image wins and the command line's file is written.
    Result both = Command("--quiet --mse-reference-image nosuch.pfm --mse-reference-out half.txt "
                          "--outfile half.exr half.pbrt", dir);
    EXPECT_EQ(both.status, 0) << both.output;
    EXPECT_TRUE(fs::exists(dir / "half.txt"));
}

TEST_F(CommandTest, PartialImagesAreWrittenAfterEveryWave) {
    Write("long.pbrt", std::string("Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 6\n"
                                   "Sampler \"independent\" \"integer pixelsamples\" 100000000\n") + kWorld);
    // Looked for while the render runs (in the background of the shell), after its first waves.
    auto existsMidway = [&](const std::string &flags, const char *file) {
        // The command line is "cd DIR && pbrt_ext ... &": the test runs outside DIR.
        Result run = Command(flags + " --time-limit 3 --outfile " + file + " long.pbrt & sleep 1.5; "
                             "test -f '" + (dir / file).string() + "' && echo MIDWAY; wait", dir);
        return run.output.find("MIDWAY") != std::string::npos;
    };
    EXPECT_TRUE(existsMidway("--quiet --write-partial-images", "partial.exr"));
    EXPECT_FALSE(existsMidway("--quiet", "final.exr"));
    EXPECT_TRUE(fs::exists(dir / "final.exr"));
}

// tev's side of the protocol (cmd/tevclient.h), decoding what one connection brings: the image
// it creates and the channel values it updates, by pixel.
struct TevImage {
    std::string name;
    int width = 0, height = 0;
    std::vector<std::string> channels;
    std::map<std::string, std::vector<float>> values;
    int updates = 0;
    std::string error;
};

TevImage DecodeTev(const std::string &bytes) {
    TevImage image;
    size_t at = 0;
    auto read = [&](auto *value) {
        std::memcpy(value, bytes.data() + at, sizeof(*value));
        at += sizeof(*value);
    };
    auto readString = [&] {
        std::string s(bytes.c_str() + at);
        at += s.size() + 1;
        return s;
    };
    while (at + 5 <= bytes.size()) {
        const size_t start = at;
        uint32_t length = 0;
        uint8_t type = 0, grabFocus = 0;
        read(&length);
        read(&type);
        read(&grabFocus);
        if (start + length > bytes.size()) {
            image.error = "a packet runs past the stream's end";
            return image;
        }
        if (type == 4) {
            image.name = readString();
            int32_t w, h, n;
            read(&w), read(&h), read(&n);
            image.width = w, image.height = h;
            for (int c = 0; c < n; ++c) image.channels.push_back(readString());
            for (const std::string &c : image.channels) image.values[c].assign(size_t(w) * h, -1);
        } else if (type == 3) {
            std::string name = readString(), channel = readString();
            int32_t x, y, w, h;
            read(&x), read(&y), read(&w), read(&h);
            if (name != image.name || !image.values.count(channel) || x < 0 || y < 0 ||
                x + w > image.width || y + h > image.height) {
                image.error = "an update outside the created image";
                return image;
            }
            for (int j = 0; j < h; ++j)
                for (int i = 0; i < w; ++i) read(&image.values[channel][size_t(y + j) * image.width + x + i]);
            ++image.updates;
        } else {
            image.error = "packet type " + std::to_string(type);
            return image;
        }
        if (at != start + length) {
            image.error = "a packet's length is not its contents'";
            return image;
        }
    }
    if (at != bytes.size()) image.error = "trailing bytes";
    return image;
}

// A TCP socket bound to a free loopback port (-1 if that fails); *port is the port.
int BoundLoopbackSocket(int *port) {
    int s = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t size = sizeof(address);
    if (s < 0 || ::bind(s, reinterpret_cast<sockaddr *>(&address), sizeof(address)) != 0 ||
        ::getsockname(s, reinterpret_cast<sockaddr *>(&address), &size) != 0)
        return -1;
    *port = ntohs(address.sin_port);
    return s;
}

TEST_F(CommandTest, TheDisplayServerGetsTheImageAsTevDecodesIt) {
    int port = 0;
    int server = BoundLoopbackSocket(&port);
    ASSERT_GE(server, 0);
    ASSERT_EQ(::listen(server, 1), 0);
    std::string received;
    std::thread viewer([&] {
        int connection = ::accept(server, nullptr, nullptr);
        if (connection < 0) return;
        char buffer[65536];
        for (ssize_t n; (n = ::read(connection, buffer, sizeof(buffer))) > 0;) received.append(buffer, size_t(n));
        ::close(connection);
    });
    Write("wide.pbrt", std::string("Film \"rgb\" \"integer xresolution\" 200 \"integer yresolution\" 3\n"
                                   "Sampler \"independent\" \"integer pixelsamples\" 2\n") + kWorld);
    Result run = Command("--quiet --outfile tev.pfm --display-server 127.0.0.1:" + std::to_string(port) +
                         " wide.pbrt", dir);
    viewer.join();
    ::close(server);
    ASSERT_EQ(run.status, 0) << run.output;
    TevImage tev = DecodeTev(received);
    ASSERT_EQ(tev.error, "");
    EXPECT_EQ(tev.name, "tev.pfm");
    ASSERT_EQ(tev.width, 200);
    ASSERT_EQ(tev.height, 3);
    EXPECT_EQ(tev.channels, (std::vector<std::string>{"R", "G", "B"}));
    // Two tiles across, three channels, after each of the two waves and at the end.
    EXPECT_EQ(tev.updates, 2 * 3 * 3);
    // What tev shows last is the image written.
    int w = 0, h = 0;
    std::vector<float> written = ReadPFM(dir / "tev.pfm", &w, &h);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 200; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(tev.values[tev.channels[c]][size_t(y) * 200 + x], written[3 * (size_t(y) * 200 + x) + c])
                    << x << ", " << y << ", " << c;
}

TEST_F(CommandTest, AMissingDisplayServerIsAWarning) {
    // A port nothing listens on: bound, never listened to.
    int port = 0;
    int s = BoundLoopbackSocket(&port);
    ASSERT_GE(s, 0);
    Result run = Command("--outfile x.pfm --display-server 127.0.0.1:" + std::to_string(port) + " scene.pbrt", dir);
    ::close(s);
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("cannot connect"), std::string::npos) << run.output;
    EXPECT_TRUE(fs::exists(dir / "x.pfm"));
}

TEST_F(CommandTest, PixelMaterialPrintsWhatThePixelSeesAndWhere) {
    // The camera sits at the sphere's centre: its ray meets the sphere from inside, 0.5 away.
    Result run = Command("--pixelmaterial 4,3 scene.pbrt", dir);
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("Intersection depth 1"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("Distance from camera: 0.5"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("Material: Material \"diffuse\" at scene.pbrt:6:1"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("Intersection depth 2"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir / "pbrt.exr"));  // no render
    Result outside = Command("--pixelmaterial 8,0 scene.pbrt", dir);
    EXPECT_EQ(outside.status, 1);
    EXPECT_NE(outside.output.find("pbrt_ext: error: --pixelmaterial: pixel (8, 0) is outside the 8 x 6 film"),
              std::string::npos) << outside.output;
}

TEST_F(CommandTest, PixelStatsCountEveryRayOfTheRender) {
    Result run = Command("--pixelstats --stats --outfile stats.exr scene.pbrt", dir);
    ASSERT_EQ(run.status, 0) << run.output;
    long long total = -1;
    size_t at = run.output.find("\nrays ");
    ASSERT_NE(at, std::string::npos) << run.output;
    std::sscanf(run.output.c_str() + at, "\nrays %lld", &total);
    Image rays = Image::Read((dir / "stats-rays.exr").string());
    Image time = Image::Read((dir / "stats-time.exr").string());
    ASSERT_EQ(rays.Resolution(), Point2i(8, 6));
    ASSERT_EQ(time.Resolution(), Point2i(8, 6));
    double sum = 0;
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) {
            EXPECT_GE(rays.GetChannel(Point2i(x, y), 0), 2) << x << ", " << y;  // a camera ray a sample
            EXPECT_GT(time.GetChannel(Point2i(x, y), 0), 0) << x << ", " << y;
            sum += rays.GetChannel(Point2i(x, y), 0);
        }
    EXPECT_EQ(sum, double(total));
}

}  // namespace
