// `!xform` as xform(1) describes it: the options are applied in the order given; `-a n`
// starts a transform stepped n times (copies 0 … n − 1), `-i n` one applied n times.

#include "transform.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra::radiance {

namespace {

constexpr double k_pi = 3.14159265358979323846;

/// Copies one `!xform` line may make: 10⁶ is far beyond a daylight model's needs and keeps a
/// typo (`-a 1e9`) from exhausting memory.
constexpr long k_max_copies = 1000000;

Affine rotation(int axis, double degrees) {
    const double a = degrees * k_pi / 180.0, c = std::cos(a), s = std::sin(a);
    const int i = (axis + 1) % 3, j = (axis + 2) % 3; // counter-clockwise seen down the axis
    Affine r;
    r.rows[i][i] = c;
    r.rows[i][j] = -s;
    r.rows[j][i] = s;
    r.rows[j][j] = c;
    return r;
}

Affine scaling(const Vec3& s) {
    Affine m;
    for (int i = 0; i < 3; ++i)
        m.rows[i][i] = s[i];
    return m;
}

/// One run of options between `-a`/`-i` markers: its transform and how often it applies.
struct Segment {
    Affine step;
    long count = 1;
    bool array = false;
};

class Options {
public:
    explicit Options(const Command& command) : command_(command) {}

    bool more() const { return next_ < command_.words.size(); }
    const std::string& peek() const { return command_.words[next_]; }
    const std::string& take() { return command_.words[next_++]; }

    double number(const std::string& option) {
        if (!more())
            fail(command_.where, fmt::format("!xform: option {} needs a number", option));
        const std::string& word = take();
        char* end = nullptr;
        const double v = std::strtod(word.c_str(), &end);
        if (*end != '\0' || word.empty() || !std::isfinite(v))
            fail(command_.where,
                 fmt::format("!xform: option {} needs a number, got '{}'", option, word));
        return v;
    }

    long count(const std::string& option) {
        const double v = number(option);
        if (v != std::floor(v) || v < 1 || v > double(k_max_copies))
            fail(command_.where, fmt::format("!xform: option {} needs a count in [1, {}], got {}",
                                             option, k_max_copies, v));
        return long(v);
    }

    const SourceLine& where() const { return command_.where; }

private:
    const Command& command_;
    std::size_t next_ = 1; // after "xform"
};

/// Applies one transform option to \p segment; false if \p option is not a transform.
bool apply_transform(const std::string& option, Options& in, Segment& segment) {
    Affine step;
    if (option == "-t") {
        for (int i = 0; i < 3; ++i)
            step.translation[i] = in.number(option);
    } else if (option == "-rx" || option == "-ry" || option == "-rz") {
        step = rotation(option[2] - 'x', in.number(option));
    } else if (option == "-s") {
        const double s = in.number(option);
        if (s == 0)
            fail(in.where(), "!xform: -s 0 collapses the scene to a point");
        step = scaling(Vec3(s, s, s));
    } else if (option == "-mx" || option == "-my" || option == "-mz") {
        Vec3 s(1, 1, 1);
        s[std::size_t(option[2] - 'x')] = -1;
        step = scaling(s);
    } else {
        return false;
    }
    segment.step = then(segment.step, step);
    return true;
}

std::vector<Affine> expand(const std::vector<Segment>& segments, const SourceLine& where) {
    std::vector<Affine> copies{Affine{}};
    for (const Segment& segment : segments) {
        if (segment.array && double(copies.size()) * double(segment.count) > k_max_copies)
            fail(where, fmt::format("!xform: more than {} copies", k_max_copies));
        std::vector<Affine> next;
        for (const Affine& copy : copies) {
            Affine current = copy;
            for (long k = 0; k < segment.count; ++k) {
                if (segment.array)
                    next.push_back(current);
                current = then(current, segment.step);
            }
            if (!segment.array)
                next.push_back(current);
        }
        copies = std::move(next);
    }
    return copies;
}

} // namespace

Vec3 Affine::point(const Vec3& p) const {
    return Vec3(dot(rows[0], p), dot(rows[1], p), dot(rows[2], p)) + translation;
}

Vec3 Affine::direction(const Vec3& d) const {
    return normalize(Vec3(dot(rows[0], d), dot(rows[1], d), dot(rows[2], d)));
}

bool Affine::mirrors() const {
    return dot(rows[0], cross(rows[1], rows[2])) < 0;
}

Affine then(const Affine& first, const Affine& second) {
    Affine r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r.rows[i][j] = second.rows[i][0] * first.rows[0][j] +
                           second.rows[i][1] * first.rows[1][j] +
                           second.rows[i][2] * first.rows[2][j];
    r.translation = second.point(first.translation);
    return r;
}

Xform parse_xform(const Command& command) {
    Options in(command);
    Xform xform;
    std::vector<Segment> segments(1);
    while (in.more() && in.peek().starts_with('-') && in.peek() != "-") {
        const std::string option = in.take();
        if (apply_transform(option, in, segments.back()))
            continue;
        if (option == "-a" || option == "-i")
            segments.push_back(Segment{.count = in.count(option), .array = option == "-a"});
        else if (option == "-I")
            xform.invert = !xform.invert;
        else if (option != "-c")
            fail(command.where,
                 fmt::format("!xform: option {} is not supported (supported: -t, -rx, -ry, -rz, "
                             "-s, -mx, -my, -mz, -a, -i, -I, -c)",
                             option));
    }
    while (in.more())
        xform.files.push_back(in.take());
    if (xform.files.empty() ||
        std::find(xform.files.begin(), xform.files.end(), "-") != xform.files.end())
        fail(command.where, "!xform: name the files to read (the standard input is not read)");
    xform.copies = expand(segments, command.where);
    return xform;
}

} // namespace penumbra::radiance
