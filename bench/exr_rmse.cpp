// exr_rmse: the RGB root-mean-square difference of two linear EXR images of one size, over the
// pixels whose reference luminance is at most 0.9 × LIGHT (the pixels that show the light
// left out, as tests/app/reference_test.cpp measures the Cornell box against Cycles).
// With --split it also prints the RMSE over the light's edge pixels (those left in that touch
// a left-out pixel, 8-neighbourhood) and over the rest; --error OUT.exr writes the per-pixel
// difference IMAGE − REFERENCE (left-out pixels 0) and --worst N lists the N pixels of largest
// squared difference, to see where the error is.
// --noise STDERR.exr (the reference's per-pixel standard error, |a − b| / 2 of its two halves)
// adds the RMSE against the converged image: the mean square difference less the reference's
// own noise variance (the mean of STDERR², an unbiased estimate of it), over the same pixels.
//
//   exr_rmse IMAGE.exr REFERENCE.exr [LIGHT_LUMINANCE] [--split] [--error OUT.exr] [--worst N]
//            [--noise STDERR.exr]
//   (radiance units, W/(sr·m²))

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/rgb.h"

namespace {

using namespace penumbra;

struct Options {
    std::string image, reference, error, noise;
    double light = std::numeric_limits<double>::infinity();
    bool split = false;
    std::size_t worst = 0;
};

Options parse(int argc, char** argv) {
    Options o;
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--split")
            o.split = true;
        else if (a == "--error" && i + 1 < argc)
            o.error = argv[++i];
        else if (a == "--noise" && i + 1 < argc)
            o.noise = argv[++i];
        else if (a == "--worst" && i + 1 < argc)
            o.worst = std::stoul(argv[++i]);
        else
            positional.push_back(a);
    }
    if (positional.size() < 2 || positional.size() > 3)
        throw std::invalid_argument("usage: exr_rmse IMAGE.exr REFERENCE.exr [LIGHT_LUMINANCE] "
                                    "[--split] [--error OUT.exr] [--worst N] [--noise STDERR.exr]");
    o.image = positional[0];
    o.reference = positional[1];
    if (positional.size() == 3)
        o.light = std::stod(positional[2]);
    return o;
}

// Per pixel: 0 measured, 1 measured on the light's edge, 2 left out (shows the light).
std::vector<int> classify(const Image& ref, double light) {
    std::vector<int> kind(ref.pixels.size(), 0);
    for (std::size_t i = 0; i < ref.pixels.size(); ++i)
        if (to_photometric(ref.pixels[i]) / k_luminous_efficacy_lm_per_w > 0.9 * light)
            kind[i] = 2;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            int& k = kind[std::size_t(y) * std::size_t(ref.width) + std::size_t(x)];
            for (int dy = -1; dy <= 1 && k == 0; ++dy)
                for (int dx = -1; dx <= 1 && k == 0; ++dx) {
                    const int u = x + dx, v = y + dy;
                    if (u >= 0 && v >= 0 && u < ref.width && v < ref.height &&
                        kind[std::size_t(v) * std::size_t(ref.width) + std::size_t(u)] == 2)
                        k = 1;
                }
        }
    return kind;
}

struct Sum {
    double squares = 0;
    std::size_t count = 0;
    double noise = 0; ///< Σ of the reference's squared standard errors (--noise)
    double rmse() const { return count ? std::sqrt(squares / double(count)) : 0.0; }
    /// Against the converged image: the reference's noise variance taken out.
    double converged_rmse() const {
        return count ? std::sqrt(std::max(0.0, squares - noise) / double(count)) : 0.0;
    }
};

double squares_of(const Rgb& d) {
    return double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b;
}

// The \p n pixels of largest squared difference: position, image and reference values.
void print_worst(const Image& image, const Image& ref, const Image& error, std::size_t n) {
    std::vector<std::size_t> order(error.pixels.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    const auto squares = [&](std::size_t i) { return squares_of(error.pixels[i]); };
    n = std::min(n, order.size());
    std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(n), order.end(),
                      [&](std::size_t a, std::size_t b) { return squares(a) > squares(b); });
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = order[k];
        const Rgb &a = image.pixels[i], &b = ref.pixels[i];
        std::printf("x %4zu y %4zu  image %.4f %.4f %.4f  reference %.4f %.4f %.4f\n",
                    i % std::size_t(ref.width), i / std::size_t(ref.width), a.r, a.g, a.b, b.r, b.g,
                    b.b);
    }
}

} // namespace

int main(int argc, char** argv) {
    try {
        const Options o = parse(argc, argv);
        const Image image = read_exr(o.image), ref = read_exr(o.reference);
        if (image.width != ref.width || image.height != ref.height) {
            std::fprintf(stderr, "exr_rmse: %dx%d against %dx%d\n", image.width, image.height,
                         ref.width, ref.height);
            return 2;
        }
        const std::optional<Image> noise =
            o.noise.empty() ? std::nullopt : std::optional<Image>(read_exr(o.noise));
        if (noise && (noise->width != ref.width || noise->height != ref.height)) {
            std::fprintf(stderr, "exr_rmse: --noise %s is not of the reference's size\n",
                         o.noise.c_str());
            return 2;
        }
        const std::vector<int> kind = classify(ref, o.light);
        Sum all, edge, rest;
        Image error(ref.width, ref.height);
        for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
            if (kind[i] == 2)
                continue;
            const Rgb d = image.pixels[i] - ref.pixels[i];
            const double s = squares_of(d), n = noise ? squares_of(noise->pixels[i]) : 0.0;
            Sum& part = kind[i] == 1 ? edge : rest;
            for (Sum* sum : {&all, &part}) {
                sum->squares += s;
                sum->noise += n;
                sum->count += 3;
            }
            error.pixels[i] = d;
        }
        if (o.split)
            std::printf("%.6f (edge: %zu pixels, RMSE %.6f; rest %.6f)\n", all.rmse(),
                        edge.count / 3, edge.rmse(), rest.rmse());
        else
            std::printf("%.6f\n", all.rmse());
        if (noise)
            std::printf("converged %.6f (edge %.6f; rest %.6f; the reference's noise %.6f)\n",
                        all.converged_rmse(), edge.converged_rmse(), rest.converged_rmse(),
                        std::sqrt(all.noise / double(std::max<std::size_t>(all.count, 1))));
        if (!o.error.empty())
            write_exr(o.error, error);
        print_worst(image, ref, error, o.worst);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "exr_rmse: %s\n", e.what());
        return 1;
    }
}
