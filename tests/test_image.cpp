// Image I/O and error metrics. Everything runs on tiny images in a private
// temporary directory, so the suite stays fast and leaves nothing behind.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vec.h"
#include "image/image.h"
#include "evaluation/error_map.h"
#include "image/exposure.h"
#include "evaluation/metrics.h"
#include "png_bytes.h"

namespace fs = std::filesystem;
using namespace tripath;

namespace {

// A fresh directory per test, removed afterwards, so tests can list it to
// prove that no temporary files were left behind.
class ImageIoTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               (std::string("tripath_test_image_") + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
        fs::remove_all(dir_, ec);
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::vector<std::string> listing() const {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path dir_;
};

std::vector<unsigned char> fileBytes(const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// The message the user sees must be a single line that names the file.
template <class F>
std::string expectInputError(F&& f, const std::string& mentions) {
    try {
        f();
    } catch (const InputError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(mentions), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        return msg;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected InputError, got: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected InputError, nothing was thrown";
    return {};
}

Image filled(int w, int h, float r, float g, float b) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            img.at(x, y)[0] = r;
            img.at(x, y)[1] = g;
            img.at(x, y)[2] = b;
        }
    return img;
}

}  // namespace

TEST(Image, ConstructorZeroFillsAndIndexesRowMajor) {
    Image img(4, 3);
    ASSERT_EQ(img.rgb.size(), 36u);
    EXPECT_TRUE(std::all_of(img.rgb.begin(), img.rgb.end(), [](float v) { return v == 0.0f; }));
    EXPECT_EQ(img.at(0, 0), img.rgb.data());
    EXPECT_EQ(img.at(1, 0), img.rgb.data() + 3);
    EXPECT_EQ(img.at(2, 1), img.rgb.data() + 3 * (4 + 2));
    EXPECT_THROW(Image(-1, 2), InputError);
}

TEST_F(ImageIoTest, ExrRoundTripIsBitExactWithMetadata) {
    // Values chosen so that a half-float or lossy path would change them:
    // beyond half range, below half precision, denormal, negative, non-dyadic.
    const std::vector<float> special = {0.0f,     1.0f,      0.1f,    1e-30f,  1e-40f, 65504.0f * 4.0f,
                                        1e6f + 1, -2.5f,     3.14159265f, 1.0e-7f, 0.5f + 1e-7f,
                                        std::numeric_limits<float>::max()};
    Image img(5, 3);
    for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = special[i % special.size()] * (1 + 0.01f * float(i));
    img.at(4, 2)[2] = 1e-30f;

    const Metadata meta = {{"tripath:integrator", "bdpt"},
                           {"tripath:spp", "1024"},
                           {"tripath:command", "tripath render --scene 'a b.gltf' --spp 1024"},
                           {"other:note", "not ours, must be filtered on read"}};
    const std::string p = path("round.exr");
    writeExr(p, img, meta);

    Metadata back;
    Image r = readExr(p, &back);
    ASSERT_EQ(r.width, img.width);
    ASSERT_EQ(r.height, img.height);
    ASSERT_EQ(r.rgb.size(), img.rgb.size());
    for (std::size_t i = 0; i < img.rgb.size(); ++i)
        EXPECT_EQ(std::memcmp(&r.rgb[i], &img.rgb[i], sizeof(float)), 0) << "index " << i << ": wrote "
                                                                         << img.rgb[i] << ", read " << r.rgb[i];

    // OpenEXR keeps header attributes sorted by name, so compare as sets.
    Metadata expected(meta.begin(), meta.begin() + 3);
    std::sort(expected.begin(), expected.end());
    std::sort(back.begin(), back.end());
    EXPECT_EQ(back, expected);
}

// Channels beside R, G and B come back under their names, each pixel's value its own, and leave
// the image read as RGB untouched: a layer written alphabetically before "R" ("A", "Z.x" after
// "B" and "G" but before "R" in OpenEXR's order) must not take R's place. Fails with the channels
// interleaved by channel instead of by pixel, or their names not set (OpenImageIO would call them
// "channel3", …).
TEST_F(ImageIoTest, ExrChannelsBesideRgbComeBackByName) {
    Image img(3, 2);
    for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = float(i) + 0.5f;
    const std::vector<ExrChannel> channels{{"auto.merge", {1, 0, 0, 1, 1, 0}}, {"A.x", {0.25f, 2, 3, 4, 5, 6}}};
    const std::string p = path("channels.exr");
    writeExr(p, img, {{"tripath:integrator", "auto"}}, channels);

    std::vector<ExrChannel> back;
    const Image r = readExr(p, nullptr, &back);
    EXPECT_EQ(r.rgb, img.rgb);
    ASSERT_EQ(back.size(), 2u);
    for (const ExrChannel& c : channels) {
        const auto it = std::find_if(back.begin(), back.end(), [&](const ExrChannel& b) { return b.name == c.name; });
        ASSERT_NE(it, back.end()) << c.name;
        EXPECT_EQ(it->values, c.values) << c.name;
    }
    expectInputError([&] { writeExr(path("short.exr"), img, {}, {{"auto.pt", {1, 0}}}); }, "auto.pt has 2 values for 6");
    expectInputError([&] { writeExr(path("r.exr"), img, {}, {{"R", std::vector<float>(6)}}); }, "named 'R'");
}

TEST_F(ImageIoTest, ExrUsesZipCompression) {
    const std::string p = path("zip.exr");
    writeExr(p, filled(8, 8, 0.25f, 0.5f, 1.5f), {});
    // The header stores: name "compression", type "compression", int32 size 1,
    // then one byte; ZIP_COMPRESSION (16-line blocks) is 3.
    const auto bytes = fileBytes(p);
    ASSERT_GE(bytes.size(), 4u);
    EXPECT_EQ(bytes[0], 0x76);  // OpenEXR magic 20000630, little-endian
    EXPECT_EQ(bytes[1], 0x2f);
    EXPECT_EQ(bytes[2], 0x31);
    EXPECT_EQ(bytes[3], 0x01);
    const std::string key("compression\0compression\0\x01\0\0\0", 28);
    auto it = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    ASSERT_NE(it, bytes.end());
    ASSERT_LT(std::distance(bytes.begin(), it) + 28, std::ptrdiff_t(bytes.size()));
    EXPECT_EQ(*(it + 28), 3);
}

TEST_F(ImageIoTest, PngHasMagicAndSrgbEncodedValues) {
    // Linear values with hand-computed sRGB codes:
    // 0.5 -> 187.52 -> 188, 0.2 -> 123.55 -> 124, 0.18 -> 117.65 -> 118,
    // 0.001 (linear segment, 12.92 * 0.001 * 255 = 3.29) -> 3,
    // anything >= 1 clamps to 255, negatives and NaN to 0.
    Image img(4, 2);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float values[8][3] = {{0.5f, 0.2f, 0.18f}, {0.001f, 1.0f, 7.0f},   {-1.0f, 0.0f, nan},
                                {0.9f, 0.25f, 0.0f}, {0.5f, 0.5f, 0.5f},     {1e9f, -1e9f, 0.0031308f},
                                {0.f, 0.f, 0.f},     {1.0f, 1.0f, 1.0f}};
    const int expected[8][3] = {{188, 124, 118}, {3, 255, 255}, {0, 0, 0},   {243, 137, 0},
                                {188, 188, 188}, {255, 0, 10},  {0, 0, 0}, {255, 255, 255}};
    for (int i = 0; i < 8; ++i)
        for (int c = 0; c < 3; ++c) img.at(i % 4, i / 4)[c] = values[i][c];

    const std::string p = path("preview.png");
    writePng(p, img);

    const auto bytes = fileBytes(p);
    const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    ASSERT_GE(bytes.size(), 8u);
    EXPECT_TRUE(std::equal(magic, magic + 8, bytes.begin()));

    Image back = readImage(p);
    ASSERT_EQ(back.width, 4);
    ASSERT_EQ(back.height, 2);
    for (int i = 0; i < 8; ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(std::lround(back.at(i % 4, i / 4)[c] * 255.0f), expected[i][c]) << "pixel " << i << " ch " << c;
}

TEST_F(ImageIoTest, PngExposureScalesByPowersOfTwo) {
    const std::string brighter = path("up.png"), darker = path("down.png");
    writePng(brighter, filled(2, 2, 0.25f, 0.125f, 0.0f), 1.0f);  // x2 -> 0.5, 0.25
    writePng(darker, filled(2, 2, 1.0f, 0.5f, 2.0f), -1.0f);      // /2 -> 0.5, 0.25, 1
    Image a = readImage(brighter), b = readImage(darker);
    EXPECT_EQ(std::lround(a.at(1, 1)[0] * 255), 188);
    EXPECT_EQ(std::lround(a.at(1, 1)[1] * 255), 137);
    EXPECT_EQ(std::lround(a.at(1, 1)[2] * 255), 0);
    EXPECT_EQ(std::lround(b.at(0, 0)[0] * 255), 188);
    EXPECT_EQ(std::lround(b.at(0, 0)[1] * 255), 137);
    EXPECT_EQ(std::lround(b.at(0, 0)[2] * 255), 255);
}

// Grey pixels of luminance 1, 2, ..., 100 in shuffled order, with black and non-finite pixels
// that the percentile leaves out.
Image greyRamp() {
    Image img(13, 10);
    for (int i = 0; i < 100; ++i) {
        const int at = (i * 37) % 100;  // 37 is prime to 100: a permutation
        std::fill_n(img.at(at % 13, at / 13), 3, float(i + 1));
    }
    std::fill_n(img.at(9, 9), 3, std::numeric_limits<float>::quiet_NaN());
    std::fill_n(img.at(10, 9), 3, std::numeric_limits<float>::infinity());
    return img;  // the remaining 28 pixels stay black
}

TEST(Exposure, PercentileIsOverThePixelsAboveZero) {
    const Image ramp = greyRamp();
    // Of the 100 positive finite values 1..100 the one at rank round(p × 99) from 0; a grey v has
    // luminance v (the Rec. 709 weights add up to 1) within float rounding.
    EXPECT_NEAR(luminancePercentile(ramp, 0.99f), 99.0f, 1e-4f);  // rank 98.01
    EXPECT_NEAR(luminancePercentile(ramp, 0.5f), 51.0f, 1e-4f);   // rank 49.5
    EXPECT_NEAR(luminancePercentile(ramp, 1.0f), 100.0f, 1e-4f);
    EXPECT_NEAR(luminancePercentile(ramp, 0.001f), 1.0f, 1e-4f);
    EXPECT_EQ(luminancePercentile(Image(4, 4), 0.99f), 0.0f);
}

TEST(Exposure, AutomaticExposureMapsThe98thPercentileToWhiteInThirdsOfAStop) {
    Image ramp = greyRamp();
    EXPECT_EQ(kAutoExposurePercentile, 0.98f);
    EXPECT_NEAR(luminancePercentile(ramp, 0.98f), 98.0f, 1e-4f);  // rank round(0.98 × 99) = 97
    for (float& v : ramp.rgb) v *= 8.0f / 98.0f;  // the 98th percentile becomes 8: -3 stops exactly
    EXPECT_NEAR(autoExposureStops(ramp), -3.0f, 1e-6f);
    for (float& v : ramp.rgb) v *= 5.0f / 8.0f;  // 5: -log2(5) = -2.32, the nearest third -7/3
    EXPECT_NEAR(autoExposureStops(ramp), -7.0f / 3.0f, 1e-6f);
    for (float& v : ramp.rgb) v *= 1.05f;  // 5 % brighter (another sample count): the same exposure
    EXPECT_NEAR(autoExposureStops(ramp), -7.0f / 3.0f, 1e-6f);
    for (float& v : ramp.rgb) v /= 5.25f * 64.0f;  // 1/64: +6 stops
    EXPECT_NEAR(autoExposureStops(ramp), 6.0f, 1e-5f);
    EXPECT_EQ(autoExposureStops(Image(4, 4)), 0.0f);  // black stays black
}

// A model lit by a point light next to it reads 100 and more: at exposure 0 its preview is a
// white silhouette. Without an exposure the 98th percentile is about white and the rest keeps its
// shades; a given exposure is kept.
TEST_F(ImageIoTest, PreviewWithoutExposureIsExposedFromTheImage) {
    const Image ramp = greyRamp();
    EXPECT_NEAR(writePreviewPng(path("auto.png"), ramp, std::nullopt), -20.0f / 3.0f, 1e-6f);
    EXPECT_EQ(writePreviewPng(path("given.png"), ramp, 0.0f), 0.0f);
    const Image automatic = readImage(path("auto.png")), given = readImage(path("given.png"));
    const float scale = std::exp2(-20.0f / 3.0f);  // -log2(98) = -6.61, rounded to -20/3
    int distinct = 0;
    for (int y = 0; y < ramp.height; ++y)
        for (int x = 0; x < ramp.width; ++x) {
            const float v = ramp.at(x, y)[0];
            if (!std::isfinite(v) || !(v > 0)) continue;
            EXPECT_EQ(given.at(x, y)[0], 1.0f);  // the silhouette
            const float expected = std::min(1.0f, v * scale);
            EXPECT_NEAR(srgbDecode(automatic.at(x, y)[0]), expected, 0.01f + 0.02f * expected) << v;
            distinct += automatic.at(x, y)[0] < 1.0f;
        }
    EXPECT_EQ(distinct, 100);  // 99 × 2^(-20/3) = 0.97 and 100 × 2^(-20/3) = 0.98: none is white
}

TEST_F(ImageIoTest, WritesLeaveNoTemporaryFilesAndReplaceTargets) {
    writeExr(path("a.exr"), filled(3, 2, 1, 2, 3), {{"tripath:run", "first"}});
    writePng(path("a.png"), filled(3, 2, 0.5f, 0.5f, 0.5f));
    // Overwriting goes through rename as well and must replace the content.
    writeExr(path("a.exr"), filled(3, 2, 4, 5, 6), {{"tripath:run", "second"}});
    EXPECT_EQ(listing(), (std::vector<std::string>{"a.exr", "a.png"}));

    Metadata meta;
    Image r = readExr(path("a.exr"), &meta);
    EXPECT_EQ(r.at(2, 1)[0], 4.0f);
    EXPECT_EQ(meta, (Metadata{{"tripath:run", "second"}}));
}

// A temporary left by a writer killed mid-write (SIGKILL leaves a checkpoint's, hundreds of MB,
// for good) is removed by the next write of its target once its process is gone; a running
// process's temporary, another target's and other files stay.
TEST_F(ImageIoTest, TheNextWriteRemovesTheTemporariesOfAKilledWriter) {
    const pid_t child = fork();
    if (child == 0) _exit(0);
    ASSERT_GT(child, 0);
    waitpid(child, nullptr, 0);  // reaped: its pid names no process
    const std::string gone = std::to_string(child), running = std::to_string(getpid());
    const std::vector<std::string> kept = {"a.exr.tmp-" + running + "-7.exr", "b.exr.tmp-" + gone + "-0.exr",
                                           "a.exr.tmp-x-0.exr", "a.exr.tmp-" + gone};
    for (const std::string& name : kept) std::ofstream(path(name)) << "x";
    std::ofstream(path("a.exr.tmp-" + gone + "-0.exr")) << "x";
    std::ofstream(path("a.exr.tmp-" + gone + "-3.part")) << "x";
    writeExr(path("a.exr"), filled(2, 2, 1, 1, 1), {});
    std::vector<std::string> expected = kept;
    expected.push_back("a.exr");
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(listing(), expected);
}

TEST_F(ImageIoTest, WriteIntoMissingDirectoryThrowsAndLeavesNothing) {
    const std::string p = path("missing/out.exr");
    expectInputError([&] { writeExr(p, filled(2, 2, 1, 1, 1), {}); }, p);
    expectInputError([&] { writePng(path("missing/out.png"), filled(2, 2, 1, 1, 1)); }, "missing/out.png");
    EXPECT_FALSE(fs::exists(path("missing")));
    EXPECT_TRUE(listing().empty());
}

TEST_F(ImageIoTest, WriteOntoDirectoryOrEmptyImageThrows) {
    fs::create_directory(path("sub.exr"));
    expectInputError([&] { writeExr(path("sub.exr"), filled(2, 2, 1, 1, 1), {}); }, "sub.exr");
    expectInputError([&] { writeExr(path("empty.exr"), Image(), {}); }, "empty.exr");
    Image bad(2, 2);
    bad.rgb.pop_back();
    expectInputError([&] { writePng(path("bad.png"), bad); }, "bad.png");
    EXPECT_EQ(listing(), (std::vector<std::string>{"sub.exr"}));
}

TEST_F(ImageIoTest, ReadErrorsAreOneLineInputErrors) {
    expectInputError([&] { readExr(path("nope.exr")); }, "nope.exr");

    const std::string corrupt = path("corrupt.exr");
    std::ofstream(corrupt, std::ios::binary) << "this is not an image\n\nat all\n";
    expectInputError([&] { readExr(corrupt); }, corrupt);
    expectInputError([&] { readImage(corrupt); }, corrupt);

    // A valid EXR cut in half: the header parses, the pixels do not.
    const std::string whole = path("whole.exr"), truncated = path("truncated.exr");
    Image noise(64, 64);
    for (std::size_t i = 0; i < noise.rgb.size(); ++i) noise.rgb[i] = float((i * 2654435761u) % 1000) / 7.0f;
    writeExr(whole, noise, {});
    auto bytes = fileBytes(whole);
    bytes.resize(bytes.size() / 2);
    std::ofstream(truncated, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    expectInputError([&] { readExr(truncated); }, truncated);

    // readExr insists on EXR; a PNG has to go through readImage.
    writePng(path("p.png"), filled(2, 2, 0.5f, 0.5f, 0.5f));
    expectInputError([&] { readExr(path("p.png")); }, "p.png");
    expectInputError([&] { readExr(dir_.string()); }, dir_.string());
}

// The bytes of an OpenEXR scan-line file whose header claims width × height pixels of half R, G, B
// with compression `compression` (OpenEXR's code: 0 none, 3 zip), followed by `chunks` zero
// offsets and nothing else: a header with no pixel data.
std::string exrHeaderOnly(int width, int height, char compression, int chunks) {
    auto i32 = [](int32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    auto attribute = [&](const std::string& name, const std::string& type, const std::string& value) {
        return name + '\0' + type + '\0' + i32(int32_t(value.size())) + value;
    };
    std::string channels;
    for (const char* c : {"B", "G", "R"}) channels += std::string(c) + '\0' + i32(1) + std::string(4, '\0') + i32(1) + i32(1);
    channels += '\0';
    const std::string box = i32(0) + i32(0) + i32(width - 1) + i32(height - 1);
    const float one = 1, zero = 0;
    const std::string f1(reinterpret_cast<const char*>(&one), 4), f0(reinterpret_cast<const char*>(&zero), 4);
    return std::string("\x76\x2f\x31\x01", 4) + i32(2) + attribute("channels", "chlist", channels) +
           attribute("compression", "compression", std::string(1, compression)) + attribute("dataWindow", "box2i", box) +
           attribute("displayWindow", "box2i", box) + attribute("lineOrder", "lineOrder", std::string(1, '\0')) +
           attribute("pixelAspectRatio", "float", f1) + attribute("screenWindowCenter", "v2f", f0 + f0) +
           attribute("screenWindowWidth", "float", f1) + '\0' + std::string(size_t(8) * size_t(chunks), '\0');
}

// A 131 KB OpenEXR file whose header claims 32768 × 16384 uncompressed pixels (3.2 GB of halves),
// and a 200-byte PNG claiming as many RGB pixels, are refused by their size before anything is
// allocated, naming what they claim; a constant image, which ZIP shrinks about 400 times, reads
// back as it was written.
TEST_F(ImageIoTest, FileFarTooSmallForItsHeaderIsRefusedUnread) {
    const std::string huge = path("huge.exr");
    std::ofstream(huge, std::ios::binary) << exrHeaderOnly(32768, 16384, 0, 16384);
    EXPECT_LT(fs::file_size(huge), 140000u);
    expectInputError([&] { readImage(huge); }, huge + "': its header claims 32768x16384 pixels");
    const std::string zip = path("zip.exr");
    std::ofstream(zip, std::ios::binary) << exrHeaderOnly(32768, 16384, 3, 1024);
    expectInputError([&] { readImage(zip); }, "(compression: zip), which take at least");
    std::string ihdr;
    test::png_detail::bigEndian(ihdr, 32768);
    test::png_detail::bigEndian(ihdr, 16384);
    ihdr += std::string("\x08\x02\0\0\0", 5);  // 8 bits, RGB, deflate, adaptive filters, not interlaced
    const std::string png = path("huge.png");
    std::ofstream(png, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) + test::png_detail::chunk("IHDR", ihdr) +
                                                test::png_detail::chunk("IDAT", test::png_detail::storedZlib(std::string(99, '\0'))) +
                                                test::png_detail::chunk("IEND", "");
    expectInputError([&] { readImage(png); }, png + "': its header claims 32768x16384 pixels, which take at least");
    const std::string constant = path("constant.exr");
    writeExr(constant, filled(1024, 512, 0.25f, 0.5f, 2.0f), {});
    EXPECT_LT(fs::file_size(constant), 1024u * 512 * 12 / 100);
    const Image back = readImage(constant);
    EXPECT_EQ(back.rgb, filled(1024, 512, 0.25f, 0.5f, 2.0f).rgb);
}

// Reading `file` (at most `maxPixels`), refused, in a child process (whose peak memory is its
// own) costs less than 1 GB.
void expectRefusedWithinAGigabyte(const std::string& file, std::size_t maxPixels = SIZE_MAX) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            try {
                readImage(file, maxPixels);
            } catch (const InputError&) {
            }
            rusage usage{};
            getrusage(RUSAGE_SELF, &usage);
            std::_Exit(usage.ru_maxrss < 1000 * 1024 ? 0 : 1);  // kilobytes
        },
        testing::ExitedWithCode(0), "")
        << file;
}

// A 400-byte OpenEXR file whose header holds a string attribute claiming 1.9 GB: OpenEXR sizes the
// string by that claim before reading it, so without a look at the header first the read costs
// 1.9 GB of memory before it fails. It is refused from its header, naming the claim, and far
// below that.
TEST_F(ImageIoTest, ExrAttributeLongerThanTheFileIsRefusedUnread) {
    constexpr int32_t kClaimed = 1900000000;
    std::string bytes = exrHeaderOnly(8, 4, 0, 4);
    bytes.insert(8, std::string("note\0string\0", 12) + std::string(reinterpret_cast<const char*>(&kClaimed), 4) + "x");
    const std::string file = path("claims.exr");
    std::ofstream(file, std::ios::binary) << bytes;
    EXPECT_LT(fs::file_size(file), 1000u);
    expectInputError([&] { readImage(file); }, file + "': its OpenEXR header claims 1900000");
    expectRefusedWithinAGigabyte(file);
}

// OpenEXR decodes a whole chunk at a time, and reserves its buffer on opening the file: lines per
// chunk × the data window's width, all channels. A 400-byte DWAA file (1 byte a chunk is all that
// compression is held to) whose window is 2^28 pixels wide and 1 high, within the texels an
// environment map may have, claims 32-line chunks of 51 GB of halves; the same window 10 million
// pixels wide claims 1.96 GB. Each is refused unopened, naming the chunk, once the chunk outweighs
// the largest image read (the pixels allowed, as RGB floats: 6.4 GB for a map, 48 MB for 4M
// pixels), rather than reserve it (address space that counts where memory is not overcommitted,
// and against the fuzzer's limit on an allocation) and fail on OpenEXR's own limit or on the
// pixel count.
TEST_F(ImageIoTest, ExrChunkLargerThanTheLargestImageIsRefusedUnread) {
    constexpr size_t kMapTexels = size_t(32768) * 16384, kFewer = size_t(1) << 22;
    const std::string wide = path("wide.exr"), strip = path("strip.exr");
    std::ofstream(wide, std::ios::binary) << exrHeaderOnly(1 << 28, 1, 8, 1) + std::string(9, '\0');
    std::ofstream(strip, std::ios::binary) << exrHeaderOnly(10223616, 1, 8, 1) + std::string(9, '\0');
    EXPECT_LT(fs::file_size(wide), 1000u);
    expectInputError([&] { readImage(wide, kMapTexels); }, wide + "': OpenEXR would decode it in chunks of 51539607552 bytes");
    expectInputError([&] { readImage(strip, kFewer); }, strip + "': OpenEXR would decode it in chunks of 1962934272 bytes");
}

// A Radiance HDR file of `width` × `height` pixels of one value, each scan line run-length
// encoded in runs of 127 pixels (the longest) and the rest: as small as such a file can be.
std::string constantHdr(int width, int height) {
    std::string line = {2, 2, char(width >> 8), char(width & 0xff)};
    for (const char component : {char(128), char(64), char(32), char(129)})  // 128, 64, 32 × 2^(129 − 136)
        for (int left = width; left > 0; left -= 127) line += {char(128 + std::min(left, 127)), component};
    std::string file = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
    for (int y = 0; y < height; ++y) file += line;
    return file;
}

// A 60-byte Radiance HDR file claiming 16384 × 8192 pixels (1.6 GB as floats) is refused by its
// size before anything is allocated, naming what it claims, and far below that; a constant image
// run-length encoded as tightly as the format allows, exactly the bound, reads back.
TEST_F(ImageIoTest, HdrFileFarTooSmallForItsHeaderIsRefusedUnread) {
    const std::string huge = path("huge.hdr");
    std::ofstream(huge, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n\x02\x02\x40";
    expectInputError([&] { readImage(huge); }, huge + "': its header claims 16384x8192 pixels, which take at least");
    expectRefusedWithinAGigabyte(huge);
    const std::string constant = path("constant.hdr");
    std::ofstream(constant, std::ios::binary) << constantHdr(1024, 512);
    const Image back = readImage(constant);
    EXPECT_EQ(back.rgb, filled(1024, 512, 1.0f, 0.5f, 0.25f).rgb);
}

TEST_F(ImageIoTest, CheckWritable) {
    EXPECT_NO_THROW(checkWritable(path("out.exr")));
    EXPECT_TRUE(listing().empty()) << "probe file left behind";

    expectInputError([&] { checkWritable(path("missing/out.exr")); }, "missing/out.exr");
    std::ofstream(path("file.txt")) << "x";
    expectInputError([&] { checkWritable(path("file.txt/out.exr")); }, "file.txt/out.exr");
    fs::create_directory(path("adir"));
    expectInputError([&] { checkWritable(path("adir")); }, "adir");
    expectInputError([&] { checkWritable(""); }, "empty");
    EXPECT_EQ(listing(), (std::vector<std::string>{"adir", "file.txt"}));
}

// A folder that refuses new files even to root: /proc is a read-only file system for creation
// (permission bits would not do in CI, which runs as root and ignores them).
TEST_F(ImageIoTest, ReadOnlyDirectoryIsRejected) {
    const std::string target = "/proc/tripath-test-out.exr";
    ASSERT_TRUE(fs::is_directory("/proc"));
    expectInputError([&] { checkWritable(target); }, target);
    expectInputError([&] { writeExr(target, filled(2, 2, 1, 1, 1), {}); }, target);
    EXPECT_FALSE(fs::exists(target));
}

TEST(Metrics, IdenticalImagesHaveZeroError) {
    Image a = filled(4, 4, 0.3f, 2.0f, 0.0f);
    ErrorMetrics m = compareImages(a, a);
    EXPECT_EQ(m.relMse, 0.0);
    EXPECT_EQ(m.mse, 0.0);
    EXPECT_EQ(m.mae, 0.0);
    // No error at all: no tail either. Catches 0/0 = NaN for a perfect render.
    EXPECT_EQ(m.tailShare, 0.0);
}

TEST(Metrics, ConstantOffsetHasKnownErrors) {
    // Exactly representable values so the expectations are exact-ish:
    // reference (0.5, 1, 2), test = reference - 0.25.
    Image ref = filled(3, 5, 0.5f, 1.0f, 2.0f);
    Image test = filled(3, 5, 0.25f, 0.75f, 1.75f);
    const double d2 = 0.0625;
    ErrorMetrics m = compareImages(test, ref);
    EXPECT_DOUBLE_EQ(m.mse, d2);
    EXPECT_DOUBLE_EQ(m.mae, 0.25);
    EXPECT_DOUBLE_EQ(m.relMse, (d2 / (0.25 + 0.01) + d2 / (1 + 0.01) + d2 / (4 + 0.01)) / 3);

    // epsilon is what keeps black reference pixels finite.
    Image black(3, 5), grey = filled(3, 5, 0.5f, 0.5f, 0.5f);
    ErrorMetrics b = compareImages(grey, black, 0.25);
    EXPECT_DOUBLE_EQ(b.relMse, 1.0);  // 0.25 / (0 + 0.25)
    EXPECT_DOUBLE_EQ(b.mse, 0.25);
    EXPECT_DOUBLE_EQ(b.mae, 0.5);
}

TEST(Metrics, MeanIsOverPixelsAndChannels) {
    // One channel of one pixel off by 3 in a 2x2 image: 12 values in all.
    Image ref(2, 2), test(2, 2);
    test.at(1, 0)[1] = 3.0f;
    ErrorMetrics m = compareImages(test, ref, 1.0);
    EXPECT_DOUBLE_EQ(m.mse, 9.0 / 12);
    EXPECT_DOUBLE_EQ(m.mae, 3.0 / 12);
    EXPECT_DOUBLE_EQ(m.relMse, 9.0 / 12);
}

// The tail share on a hand-made 1000-pixel image (k = 1 pixel): 998 pixels with a small error,
// a bright pixel A with the largest absolute (and squared) error but a small relative one, and a
// dark pixel B with the largest relative error. The tail is B alone, and its share is e_B over
// the sum of every pixel's relative squared error, the same sum that relMSE is the mean of.
// Catches: ranking or summing absolute or squared instead of relative errors (A would be the
// tail), forgetting to divide by the total (100, or 100/3000), dividing by the pixel count.
TEST(Metrics, TailShareIsTheWorstPixelsShareOfTheRelativeError) {
    const int w = 40, h = 25;  // 1000 pixels
    Image ref = filled(w, h, 1, 1, 1), test = filled(w, h, 1.5f, 1, 1);
    for (int c = 0; c < 3; ++c) ref.at(3, 4)[c] = test.at(3, 4)[c] = 10.0f;
    test.at(3, 4)[0] = 12.0f;  // A: |x - r| = 2 on r = 10
    for (int c = 0; c < 3; ++c) ref.at(20, 7)[c] = test.at(20, 7)[c] = 0.0f;
    test.at(20, 7)[0] = 1.0f;  // B: |x - r| = 1 on r = 0
    const double eBackground = 0.25 / 1.01, eA = 4 / 100.01, eB = 1 / 0.01;
    const double total = 998 * eBackground + eA + eB;

    const ErrorMetrics m = compareImages(test, ref);  // epsilon 0.01
    EXPECT_NEAR(m.tailShare, eB / total, 1e-12);      // 0.288...
    EXPECT_NEAR(m.relMse, total / 3000, 1e-12);
    EXPECT_GT(m.tailShare, 0.25);
    EXPECT_LT(m.tailShare, 0.3);
}

// relMSE without the worst 0.1 %: on the same 1000-pixel image the tail is B alone, so what is
// left is the 998 background pixels and A, over 3 × 999 values. Catches: leaving out the
// brightest pixel (A) instead of the worst relative error, dividing by all 3000 values.
TEST(Metrics, RelMseWithoutTailLeavesOutTheWorstPixels) {
    const int w = 40, h = 25;
    Image ref = filled(w, h, 1, 1, 1), test = filled(w, h, 1.5f, 1, 1);
    for (int c = 0; c < 3; ++c) ref.at(3, 4)[c] = test.at(3, 4)[c] = 10.0f;
    test.at(3, 4)[0] = 12.0f;
    for (int c = 0; c < 3; ++c) ref.at(20, 7)[c] = test.at(20, 7)[c] = 0.0f;
    test.at(20, 7)[0] = 1.0f;
    const double eBackground = 0.25 / 1.01, eA = 4 / 100.01;
    EXPECT_NEAR(relMseWithoutTail(compareImages(test, ref), 1000), (998 * eBackground + eA) / 2997, 1e-12);
}

// The error map's scale (evaluation/error_map.h): the ends clamp to the first and last colours, and the
// colours brighten decade by decade. A pixel whose channels are all off by d on a reference of 1
// has e = d² / 1.01; at e = 1e-2, 0.4 of the way up the 5-decade scale, the colour is 0.6 of the way
// from the second stop (87, 16, 110) to the third (188, 55, 84): (148, 39, 94) in sRGB. Catches a
// channel sum for the mean (e three times larger), a linear scale, a scale of other ends.
TEST(ErrorMap, ColoursFollowTheLogScaleOfThePixelsRelativeSquaredError) {
    auto same = [](Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; };
    EXPECT_TRUE(same(errorColour(0), fromSrgb(0, 0, 4)));
    EXPECT_TRUE(same(errorColour(1e-5), errorColour(kErrorMapLow)));
    EXPECT_TRUE(same(errorColour(1e3), fromSrgb(252, 255, 164)));
    double previous = -1;
    for (double e = 1e-4; e <= 10; e *= 10) {
        const Rgb c = errorColour(e);
        const double y = luminance(Spectrum(c.r, c.g, c.b));
        EXPECT_GT(y, previous) << e;
        previous = y;
    }
    Image ref = filled(4, 2, 1, 1, 1), test = ref;
    const float d = float(std::sqrt(1e-2 * 1.01));
    for (int c = 0; c < 3; ++c) test.at(2, 1)[c] += d;
    const Image map = errorMap(test, ref);
    const Rgb expected = fromSrgb(148, 39, 94), zero = fromSrgb(0, 0, 4);
    EXPECT_NEAR(map.at(2, 1)[0], expected.r, 1e-6);
    EXPECT_NEAR(map.at(2, 1)[1], expected.g, 1e-6);
    EXPECT_NEAR(map.at(2, 1)[2], expected.b, 1e-6);
    EXPECT_EQ(map.at(0, 0)[0], zero.r);
    EXPECT_THROW(errorMap(filled(3, 2, 1, 1, 1), ref), InputError);
}

// srgbDecode is the inverse of the PNG writer's encoding on every 8-bit code, so an image drawn
// in sRGB bytes (the chart) is written back to the same bytes. Catches a 2.2 gamma for the sRGB
// curve, or a decode that misses its linear segment.
TEST_F(ImageIoTest, SrgbDecodeRoundTripsEveryByteThroughTheWriter) {
    Image codes(256, 1);
    for (int v = 0; v < 256; ++v)
        for (int c = 0; c < 3; ++c) codes.at(v, 0)[c] = srgbDecode(v / 255.0f);
    writePng(path("codes.png"), codes);
    const Image back = readImage(path("codes.png"));
    for (int v = 0; v < 256; ++v) EXPECT_EQ(std::lround(back.at(v, 0)[0] * 255.0f), v) << v;
    EXPECT_EQ(srgbDecode(0.0f), 0.0f);
    EXPECT_EQ(srgbDecode(1.0f), 1.0f);
}

// How many pixels the worst 0.1 % is: ceil(N / 1000), and at least one. Checked directly and
// through the metric, with two pixels of equal error (share 1/2 when the tail is one pixel, 1
// when it is two). Catches: floor(N / 1000) (1001 pixels: one pixel, 0.5), N / 1000 + 1 (1000
// pixels: two, 1.0), no lower bound of one pixel (a 2x2 image: an empty tail, 0).
TEST(Metrics, TailIsTheCeilingOfATenthOfAPercentOfThePixels) {
    EXPECT_EQ(tailPixelCount(1), 1u);
    EXPECT_EQ(tailPixelCount(4), 1u);
    EXPECT_EQ(tailPixelCount(1000), 1u);
    EXPECT_EQ(tailPixelCount(1001), 2u);
    EXPECT_EQ(tailPixelCount(2000), 2u);
    EXPECT_EQ(tailPixelCount(2001), 3u);
    EXPECT_EQ(tailPixelCount(256 * 256), 66u);

    auto twoEqualErrors = [](int w, int h) {
        Image ref(w, h), test(w, h);
        test.at(0, 0)[1] = 2.0f;
        test.at(w - 1, h - 1)[1] = 2.0f;
        return compareImages(test, ref, 1.0).tailShare;
    };
    EXPECT_DOUBLE_EQ(twoEqualErrors(40, 25), 0.5);  // 1000 pixels: the tail is one of the two
    EXPECT_DOUBLE_EQ(twoEqualErrors(7, 143), 1.0);  // 1001 pixels: both
    EXPECT_DOUBLE_EQ(twoEqualErrors(2, 2), 0.5);    // 4 pixels: still one pixel

    Image ref(2, 2), test(2, 2);
    test.at(1, 1)[2] = 3.0f;  // e = 9
    test.at(0, 1)[0] = 1.0f;  // e = 1
    EXPECT_DOUBLE_EQ(compareImages(test, ref, 1.0).tailShare, 0.9);
}

// The tail ranks pixels by the sum of their three channels' terms, not single channel values.
// P has relative squared error 1 in each channel (e = 3), Q 2.25 in one (e = 2.25): the worst
// pixel is P, share 3/5.25. Ranking the 3000 channel values would give Q's 2.25/5.25 (one value)
// or (2.25 + 1 + 1)/5.25 (three values).
TEST(Metrics, TailRanksPixelsNotChannels) {
    Image ref(40, 25), test(40, 25);
    for (int c = 0; c < 3; ++c) test.at(5, 5)[c] = 1.0f;  // P
    test.at(30, 20)[2] = 1.5f;                             // Q
    const ErrorMetrics m = compareImages(test, ref, 1.0);
    EXPECT_DOUBLE_EQ(m.tailShare, 3 / 5.25);
    EXPECT_DOUBLE_EQ(m.relMse, 5.25 / 3000);
}

// A NaN anywhere makes the tail share NaN, like relMSE: catches a partial sort that silently
// ranks the NaN somewhere and reports a plausible share.
TEST(Metrics, TailShareOfANanImageIsNan) {
    Image ref = filled(4, 4, 1, 1, 1), test = filled(4, 4, 2, 1, 1);
    test.at(2, 1)[1] = std::numeric_limits<float>::quiet_NaN();
    const ErrorMetrics m = compareImages(test, ref);
    EXPECT_TRUE(std::isnan(m.relMse));
    EXPECT_TRUE(std::isnan(m.tailShare));
}

// relMSE x spp on the error an unbiased estimator would have after N samples: every pixel off by
// sigma / sqrt(N) (alternating sign) against a reference of 1, with per-sample standard deviation
// sigma = 0.5. relMSE falls like 1/N, relMSE x N stays at sigma^2 / (1 + epsilon) whatever N.
// Catches dividing by spp, or multiplying by anything but the sample count (such as spp^2).
TEST(Metrics, RelMseTimesSppIsThePerSampleRelativeVariance) {
    const double sigma2 = 0.25, expected = sigma2 / 1.01;
    for (int n : {4, 16, 64}) {
        Image ref = filled(4, 3, 1, 1, 1), test(4, 3);
        const float d = float(std::sqrt(sigma2 / n));  // 0.25, 0.125, 0.0625: exact in float
        for (std::size_t i = 0; i < test.rgb.size(); ++i) test.rgb[i] = 1.0f + (i % 2 ? d : -d);
        const ErrorMetrics m = compareImages(test, ref);
        EXPECT_DOUBLE_EQ(m.relMse, expected / n) << n;
        EXPECT_DOUBLE_EQ(perSampleRelVariance(m.relMse, n), expected) << n;
    }
    EXPECT_DOUBLE_EQ(perSampleRelVariance(0.05, 173), 8.65);
}

TEST(Metrics, SizeMismatchThrows) {
    expectInputError([] { compareImages(Image(4, 4), Image(4, 5)); }, "4x5");
    expectInputError([] { compareImages(Image(4, 4), Image(5, 4)); }, "5x4");
}

TEST(Metrics, CropCopiesTheWindow) {
    Image img(5, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y)[c] = float(100 * y + 10 * x + c);
    Image c = crop(img, 1, 2, 3, 2);
    ASSERT_EQ(c.width, 3);
    ASSERT_EQ(c.height, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(c.at(x, y)[ch], img.at(x + 1, y + 2)[ch]);

    EXPECT_EQ(crop(img, 0, 0, 5, 4).rgb, img.rgb);
    EXPECT_THROW(crop(img, 3, 0, 3, 1), InputError);
    EXPECT_THROW(crop(img, 0, 3, 1, 2), InputError);
    EXPECT_THROW(crop(img, -1, 0, 1, 1), InputError);
    EXPECT_THROW(crop(img, 0, 0, 0, 1), InputError);
}
