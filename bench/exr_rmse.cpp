// exr_rmse: the RGB root-mean-square difference of two linear EXR images of one size, over the
// pixels whose reference luminance is at most 0.9 × LIGHT (the pixels that show the light
// left out, as tests/app/reference_test.cpp measures the Cornell box against Cycles).
//
//   exr_rmse IMAGE.exr REFERENCE.exr [LIGHT_LUMINANCE]      (radiance units, W/(sr·m²))

#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>

#include "core/image.h"
#include "core/rgb.h"

int main(int argc, char** argv) {
    using namespace penumbra;
    if (argc != 3 && argc != 4) {
        std::fprintf(stderr, "usage: exr_rmse IMAGE.exr REFERENCE.exr [LIGHT_LUMINANCE]\n");
        return 2;
    }
    try {
        const Image image = read_exr(argv[1]), ref = read_exr(argv[2]);
        if (image.width != ref.width || image.height != ref.height) {
            std::fprintf(stderr, "exr_rmse: %dx%d against %dx%d\n", image.width, image.height,
                         ref.width, ref.height);
            return 2;
        }
        const double light =
            argc == 4 ? std::stod(argv[3]) : std::numeric_limits<double>::infinity();
        double sum = 0;
        std::size_t count = 0;
        for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
            if (to_photometric(ref.pixels[i]) / k_luminous_efficacy_lm_per_w > 0.9 * light)
                continue;
            const Rgb d = image.pixels[i] - ref.pixels[i];
            sum += double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b;
            count += 3;
        }
        std::printf("%.6f\n", std::sqrt(sum / double(count)));
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "exr_rmse: %s\n", e.what());
        return 1;
    }
}
