// Image files: linear float RGB OpenEXR (OpenEXR 3 scanline API) and tone-mapped 8-bit sRGB
// PNG (libpng's simplified API, which reports errors through a message instead of longjmp).
// Automatic exposure follows Reinhard et al. 2002 (log-average luminance mapped to the key
// value 0.18), skipping black pixels instead of adding a small delta inside the logarithm.

#include "core/image.h"

#include "core/error.h"
#include "core/files.h"

#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

namespace {

void check_image(const Image& image, const char* function, const std::string& path) {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != std::size_t(image.width) * std::size_t(image.height))
        throw InternalError(fmt::format("{}('{}'): image of {}x{} with {} pixels", function, path,
                                        image.width, image.height, image.pixels.size()));
}

/// The R, G and B slices of \p pixels laid out over \p window (row-major, top row first).
Imf::FrameBuffer rgb_frame_buffer(const Rgb* pixels, const Imath::Box2i& window) {
    const std::pair<const char*, const float*> channels[] = {
        {"R", &pixels->r}, {"G", &pixels->g}, {"B", &pixels->b}};
    const std::size_t width = std::size_t(window.max.x - window.min.x + 1);
    Imf::FrameBuffer frame;
    for (const auto& [name, base] : channels)
        frame.insert(name,
                     Imf::Slice::Make(Imf::FLOAT, base, window, sizeof(Rgb), sizeof(Rgb) * width));
    return frame;
}

// The pixels as R, G, B halves, rounded to nearest; values beyond the largest half (65 504)
// are clamped to it rather than written as +inf, which a reader would take for a broken pixel.
std::vector<Imath::half> to_half(const Image& image) {
    std::vector<Imath::half> out;
    out.reserve(3 * image.pixels.size());
    for (const Rgb& c : image.pixels)
        for (int k = 0; k < 3; ++k)
            out.emplace_back(std::min(c[k], float(HALF_MAX)));
    return out;
}

/// The R, G and B slices of interleaved halves laid out over \p window.
Imf::FrameBuffer half_frame_buffer(const Imath::half* halves, const Imath::Box2i& window) {
    const std::size_t width = std::size_t(window.max.x - window.min.x + 1);
    const std::size_t pixel = 3 * sizeof(Imath::half);
    Imf::FrameBuffer frame;
    int k = 0;
    for (const char* name : {"R", "G", "B"})
        frame.insert(name, Imf::Slice::Make(Imf::HALF, halves + k++, window, pixel, pixel * width));
    return frame;
}

/// OpenEXR's output through a FileWriter, so that a failed write reports the system's reason;
/// OpenEXR's own stream says only "Error writing" when the disk is full.
class ExrOutput final : public Imf::OStream {
public:
    explicit ExrOutput(FileWriter& file, const std::string& path)
        : Imf::OStream(path.c_str()), file_(file) {}
    void write(const char c[], int n) override { file_.write(c, std::size_t(n)); }
    std::uint64_t tellp() override { return file_.position(); }
    void seekp(std::uint64_t position) override { file_.seek(position); }

private:
    FileWriter& file_;
};

std::uint8_t encode_srgb(double linear) {
    if (!(linear > 0))
        return 0; // also NaN
    if (linear >= 1)
        return 255;
    double s = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return std::uint8_t(std::lround(s * 255.0));
}

} // namespace

void write_exr(const std::string& path, const Image& image, ExrPixels pixels) {
    check_image(image, "write_exr", path);
    write_atomically(path, [&](const std::string& temp) {
        FileWriter output(temp, path);
        try {
            Imf::Header header(image.width, image.height);
            header.compression() = Imf::ZIP_COMPRESSION;
            const bool half = pixels == ExrPixels::half;
            for (const char* name : {"R", "G", "B"})
                header.channels().insert(name, Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
            ExrOutput stream(output, path);
            Imf::OutputFile file(stream, header);
            // Writing converts no pixel types: half channels get a frame buffer of halves.
            const std::vector<Imath::half> halves =
                half ? to_half(image) : std::vector<Imath::half>{};
            file.setFrameBuffer(half ? half_frame_buffer(halves.data(), header.dataWindow())
                                     : rgb_frame_buffer(image.pixels.data(), header.dataWindow()));
            file.writePixels(image.height);
        } catch (const std::exception& e) {
            if (output.error())
                output.rethrow();
            throw ExternalError(fmt::format("cannot write OpenEXR file '{}': {}", path, e.what()));
        }
        // The file's destructor wrote the line offsets and swallows any error: close() reports it.
        output.close();
    });
}

Image read_exr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imf::ChannelList& channels = file.header().channels();
        if (!channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B"))
            throw ExternalError(fmt::format("OpenEXR file '{}' has no R, G or B channel", path));
        const Imath::Box2i window = file.header().dataWindow();
        Image image(window.max.x - window.min.x + 1, window.max.y - window.min.y + 1);
        file.setFrameBuffer(rgb_frame_buffer(image.pixels.data(), window));
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const ExternalError&) {
        throw;
    } catch (const std::exception& e) {
        throw ExternalError(fmt::format("cannot read OpenEXR file '{}': {}", path, e.what()));
    }
}

double auto_exposure(const Image& image) {
    double sum_log = 0;
    std::size_t count = 0;
    for (const Rgb& p : image.pixels) {
        double y = k_lum_weight_r * p.r + k_lum_weight_g * p.g + k_lum_weight_b * p.b;
        if (!(y > 0) || !std::isfinite(y))
            continue;
        sum_log += std::log(y);
        ++count;
    }
    return count == 0 ? 1.0 : 0.18 / std::exp(sum_log / double(count));
}

void write_png(const std::string& path, const Image& image, double exposure) {
    check_image(image, "write_png", path);
    if (!(exposure > 0) || !std::isfinite(exposure))
        throw ConfigError(
            fmt::format("write_png('{}'): exposure {} must be positive", path, exposure));
    std::vector<std::uint8_t> bytes(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            bytes[3 * i + std::size_t(c)] = encode_srgb(image.pixels[i][c] * exposure);
    write_png_rgb8(path, image.width, image.height, bytes);
}

void write_png_rgb8(const std::string& path, int width, int height,
                    const std::vector<std::uint8_t>& rgb) {
    if (width <= 0 || height <= 0 || rgb.size() != 3 * std::size_t(width) * std::size_t(height))
        throw InternalError(fmt::format("write_png_rgb8('{}'): {} bytes for {}x{} pixels", path,
                                        rgb.size(), width, height));
    // Encoded in memory, then written by write_text_file: libpng's own file output reports a
    // full disk as "Write Error", without the reason.
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = png_uint_32(width);
    png.height = png_uint_32(height);
    png.format = PNG_FORMAT_RGB;
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
    // Uninitialised: only the encoded bytes are touched, so the bound costs address space only.
    const std::unique_ptr<char[]> encoded(new char[size]);
    const bool ok =
        png_image_write_to_memory(&png, encoded.get(), &size, 0, rgb.data(), 0, nullptr);
    const std::string message = png.message;
    png_image_free(&png);
    if (!ok)
        throw ExternalError(fmt::format("cannot write PNG file '{}': {}", path, message));
    write_text_file(path, std::string_view(encoded.get(), size));
}

} // namespace penumbra
