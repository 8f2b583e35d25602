// Binary file of a hierarchical solve's state (see state/solver_state.h): a magic word and version,
// then the fields in order, each vector as its element count and raw elements, then a 64-bit
// checksum of all the bytes before it.

#include "state/solver_state.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <span>
#include <sstream>
#include <string_view>

#include "core/error.h"
#include "core/files.h"
#include "core/rng.h"

namespace penumbra::solver {

namespace {

// Version 4: cluster links index the face-cluster tree, and their kernels are calibrated.
// Version 5: element links are 16 bytes (the occlusion flag is the spread's sign bit).
// Version 8: cluster links are 32 bytes (their visible fraction in 16 bits).
// Version 9: a checksum follows the fields, so that a corrupted file is refused, not solved.
constexpr char k_magic[8] = {'P', 'N', 'B', 'R', 'H', 'R', 'S', '9'};

class Writer {
public:
    explicit Writer(std::ostream& out) : out_(out) {}
    template <typename T> void pod(const T& value) {
        out_.write(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    template <typename T> void vec(std::span<const T> values) {
        pod(std::uint64_t(values.size()));
        out_.write(reinterpret_cast<const char*>(values.data()),
                   std::streamsize(values.size() * sizeof(T)));
    }
    template <typename T> void vec(const std::vector<T>& values) {
        vec(std::span<const T>(values));
    }

private:
    std::ostream& out_;
};

[[noreturn]] void fail_not_a_state(const std::string& path, const std::string& what) {
    throw InputError(path, "",
                     "not a Penumbra solver state (" + what +
                         "): bake again with the hierarchical method");
}

class Reader {
public:
    Reader(std::string bytes, std::string path)
        : bytes_(std::move(bytes)), path_(std::move(path)) {}
    template <typename T> T pod() {
        T value;
        take(&value, sizeof(T));
        return value;
    }
    template <typename T> std::vector<T> vec() {
        std::vector<T> values(count<T>());
        take(values.data(), values.size() * sizeof(T));
        return values;
    }
    template <typename T> void vec(MappedArray<T>& values) {
        values.resize(count<T>());
        take(values.data(), values.size() * sizeof(T));
    }
    void take(void* out, std::size_t n) {
        if (n > bytes_.size() - at_)
            fail("truncated or corrupt");
        if (n > 0) // an empty array's data() may be null, which memcpy must not get
            std::memcpy(out, bytes_.data() + at_, n);
        at_ += n;
    }
    bool done() const { return at_ == bytes_.size(); }
    /// The element count of the array that follows, checked against what is left.
    template <typename T> std::size_t count() {
        const auto n = pod<std::uint64_t>();
        if (n > (bytes_.size() - at_) / sizeof(T))
            fail("truncated or corrupt");
        return std::size_t(n);
    }
    [[noreturn]] void fail(const std::string& what) const { fail_not_a_state(path_, what); }

private:
    std::string bytes_, path_;
    std::size_t at_ = 0;
};

/// Refuses another version's file, a file that is not a state, and one whose checksum does not
/// match its bytes (a corruption the size checks of Reader would not see).
void check_magic_and_checksum(const std::string& bytes, const std::string& path) {
    if (bytes.size() < sizeof(k_magic))
        fail_not_a_state(path, "truncated or corrupt");
    if (std::memcmp(bytes.data(), k_magic, sizeof(k_magic) - 1) == 0 &&
        bytes[sizeof(k_magic) - 1] != k_magic[sizeof(k_magic) - 1])
        fail_not_a_state(path,
                         "written by another version of penumbra: bake again without --reuse");
    if (std::memcmp(bytes.data(), k_magic, sizeof(k_magic)) != 0)
        fail_not_a_state(path, "bad magic word");
    if (bytes.size() < sizeof(k_magic) + sizeof(std::uint64_t))
        fail_not_a_state(path, "truncated or corrupt");
    const std::string_view payload(bytes.data(), bytes.size() - sizeof(std::uint64_t));
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + payload.size(), sizeof(stored));
    if (stored != state_checksum(payload))
        throw InputError(path, "", "is corrupt (checksum mismatch): bake without --reuse");
}

} // namespace

// Chained mix64 of the bytes' 64-bit words and their count. Each step is a bijection of the
// running hash, so a change confined to one word always changes the result.
std::uint64_t state_checksum(std::string_view bytes) {
    std::uint64_t h = hash_words({bytes.size()});
    for (std::size_t at = 0; at < bytes.size(); at += sizeof(std::uint64_t)) {
        std::uint64_t word = 0;
        std::memcpy(&word, bytes.data() + at, std::min(sizeof(word), bytes.size() - at));
        h = mix64(h ^ mix64(word + 0x632be59bd9b4e019ULL));
    }
    return h;
}

std::uint64_t mesh_geometry_hash(const RadiosityMesh& mesh) {
    std::uint64_t h = hash_words({mesh.element_count(), mesh.vertex_count()});
    auto add = [&h](std::uint64_t w) { h = mix64(h ^ mix64(w + 0x632be59bd9b4e019ULL)); };
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        for (std::uint32_t v : mesh.triangles[e]) {
            const Vec3 p = mesh.vertex(v);
            add(std::bit_cast<std::uint64_t>(p.x));
            add(std::bit_cast<std::uint64_t>(p.y));
            add(std::bit_cast<std::uint64_t>(p.z));
        }
        add(mesh.element_patch[e]);
        add(std::uint64_t(std::int64_t(mesh.element_twin[e])));
    }
    return h;
}

void write_hierarchical_state(const HierarchicalState& s, const std::string& path) {
    std::ostringstream out(std::ios::binary);
    {
        Writer w(out);
        out.write(k_magic, sizeof(k_magic));
        w.pod(s.mesh_hash);
        w.pod(std::uint8_t(s.clustered ? 1 : 0));
        const Hierarchy& h = s.hierarchy;
        w.pod(std::uint64_t(h.root_count));
        w.pod(h.diagonal);
        w.vec(h.triangle);
        w.vec(h.normal);
        w.vec(h.area);
        w.vec(h.patch);
        w.vec(h.parent);
        w.vec(h.first_child);
        w.vec(h.level);
        w.vec(h.twin);
        w.vec(s.links.span());
        w.vec(s.cluster_links.span());
        w.vec(s.radiosity);
        w.vec(s.weights.offset);
        w.vec(s.weights.receive);
        w.vec(s.weights.emit);
        w.vec(s.weights.raw_receive);
        w.vec(s.weights.raw_emit);
        w.vec(s.weights.signature);
    }
    std::string bytes = std::move(out).str();
    const std::uint64_t sum = state_checksum(bytes);
    bytes.append(reinterpret_cast<const char*>(&sum), sizeof(sum));
    write_text_file(path, bytes); // binary-safe, and atomic
}

std::shared_ptr<const HierarchicalState> read_hierarchical_state(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(path, "",
                         "cannot open the solver state (bake with the hierarchical "
                         "method first; it writes solver_state.bin)");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    std::string bytes = std::move(buffer).str();
    check_magic_and_checksum(bytes, path);
    bytes.resize(bytes.size() - sizeof(std::uint64_t));
    Reader r(std::move(bytes), path);
    char magic[sizeof(k_magic)];
    r.take(magic, sizeof(magic));
    auto s = std::make_shared<HierarchicalState>();
    s->mesh_hash = r.pod<std::uint64_t>();
    s->clustered = r.pod<std::uint8_t>() != 0;
    Hierarchy& h = s->hierarchy;
    h.root_count = std::size_t(r.pod<std::uint64_t>());
    h.diagonal = r.pod<double>();
    h.triangle = r.vec<std::array<Vec3, 3>>();
    h.normal = r.vec<Vec3>();
    h.area = r.vec<double>();
    h.patch = r.vec<std::uint32_t>();
    h.parent = r.vec<std::int32_t>();
    h.first_child = r.vec<std::int32_t>();
    h.level = r.vec<std::int32_t>();
    h.twin = r.vec<std::int32_t>();
    r.vec(s->links);
    r.vec(s->cluster_links);
    s->radiosity = r.vec<Rgb>();
    LeafWeights& lw = s->weights;
    lw.offset = r.vec<std::uint32_t>();
    lw.receive = r.vec<float>();
    lw.emit = r.vec<float>();
    lw.raw_receive = r.vec<float>();
    lw.raw_emit = r.vec<float>();
    lw.signature = r.vec<std::uint64_t>();
    const std::size_t n = h.triangle.size();
    const std::size_t entries = lw.offset.empty() ? 0 : lw.offset.back();
    const bool weights_consistent =
        lw.offset.empty()
            ? lw.receive.empty() && lw.signature.empty()
            : lw.offset.size() == n + 1 && lw.receive.size() == entries &&
                  lw.emit.size() == entries && lw.raw_receive.size() == entries &&
                  lw.raw_emit.size() == entries && lw.signature.size() == n &&
                  h.first_child.size() == n && h.level.size() == n && [&] {
                      for (std::size_t x = 0; x < n; ++x) // a leaf: one entry per ancestor
                          if (lw.offset[x + 1] - lw.offset[x] !=
                              std::uint32_t(h.first_child[x] < 0 ? h.level[x] : 0))
                              return false;
                      return true;
                  }();
    const bool consistent = h.normal.size() == n && h.area.size() == n && h.patch.size() == n &&
                            h.parent.size() == n && h.first_child.size() == n &&
                            h.level.size() == n && h.twin.size() == n && s->radiosity.size() == n &&
                            h.root_count <= n && weights_consistent && r.done();
    if (!consistent)
        r.fail("inconsistent sizes");
    const auto in_range = [n](std::uint32_t node) { return node < n; };
    for (const Link& l : s->links)
        if (!in_range(l.receiver) || !in_range(l.source))
            r.fail("link to a missing node");
    h.emission.assign(n, Rgb{});
    h.reflectance.assign(n, Rgb{});
    h.transmittance.assign(n, Rgb{});
    h.opaque.assign(n, 1);
    return s;
}

} // namespace penumbra::solver
