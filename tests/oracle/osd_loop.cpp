// OpenSubdiv oracle for Loop subdivision (docs/math.md §7; docs/loop.md
// "Checked by OpenSubdiv"). Compiled and run by
// crates/kernel/tests/osd_oracle.rs against Debian's libosd-dev (OpenSubdiv
// 3.5):
//
//   g++ -O2 -std=c++14 osd_loop.cpp -o osd_loop -losdCPU
//
// Usage:
//   osd_loop eval  RULE REAL IN.obj LEVELS OUT
//       writes OUT.limit (OpenSubdiv's limit position of every vertex of IN,
//       Far::PrimvarRefiner::Limit on the unrefined mesh) and OUT.1 … OUT.LEVELS
//       (the vertices of each uniformly refined level), one "x y z" line each.
//   osd_loop bench RULE IN.obj LEVELS REPS
//       prints one line per level k = 1..LEVELS: "k vertices best_seconds", the
//       best of REPS runs of: building the TopologyRefiner from the face list,
//       RefineUniform(k), Interpolate level by level (float positions; one thread).
//
// RULE: edge-only | edge-and-corner | none (Sdc VTX_BOUNDARY_*); REAL: float | double.
// IN: an OBJ of triangles ("v x y z", "f a b c" with 1-based indices, "a/b/c" allowed).
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace OpenSubdiv;

template <typename R>
struct Vertex {
    R p[3];
    void Clear(void* = 0) { p[0] = p[1] = p[2] = 0; }
    template <typename W>
    void AddWithWeight(Vertex const& s, W w) {
        p[0] += (R)(w * s.p[0]);
        p[1] += (R)(w * s.p[1]);
        p[2] += (R)(w * s.p[2]);
    }
};

struct Mesh {
    std::vector<double> pos;
    std::vector<int> idx;
};

static void fail(std::string const& m) {
    std::fprintf(stderr, "osd_loop: %s\n", m.c_str());
    std::exit(2);
}

static Mesh read_obj(char const* path) {
    std::ifstream in(path);
    if (!in) fail(std::string("cannot read ") + path);
    Mesh m;
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        std::istringstream ss(line);
        std::string tag;
        if (!(ss >> tag)) continue;
        if (tag == "v") {
            double x, y, z;
            if (!(ss >> x >> y >> z)) fail(std::string(path) + ":" + std::to_string(lineno) + ": bad v line");
            m.pos.push_back(x);
            m.pos.push_back(y);
            m.pos.push_back(z);
        } else if (tag == "f") {
            std::string w;
            int n = 0;
            while (ss >> w) {
                m.idx.push_back(std::atoi(w.c_str()) - 1);
                ++n;
            }
            if (n != 3) fail(std::string(path) + ":" + std::to_string(lineno) + ": not a triangle");
        }
    }
    return m;
}

static Sdc::Options::VtxBoundaryInterpolation rule(std::string const& r) {
    if (r == "edge-only") return Sdc::Options::VTX_BOUNDARY_EDGE_ONLY;
    if (r == "edge-and-corner") return Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER;
    if (r == "none") return Sdc::Options::VTX_BOUNDARY_NONE;
    fail("unknown rule " + r + " (edge-only, edge-and-corner, none)");
    return Sdc::Options::VTX_BOUNDARY_NONE;
}

static Far::TopologyRefiner* refiner(Mesh const& m, std::vector<int>& counts,
                                     Sdc::Options::VtxBoundaryInterpolation b) {
    Far::TopologyDescriptor desc;
    desc.numVertices = (int)(m.pos.size() / 3);
    desc.numFaces = (int)(m.idx.size() / 3);
    counts.assign(desc.numFaces, 3);
    desc.numVertsPerFace = counts.data();
    desc.vertIndicesPerFace = m.idx.data();
    Sdc::Options o;
    o.SetVtxBoundaryInterpolation(b);
    typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> F;
    Far::TopologyRefiner* r = F::Create(desc, F::Options(Sdc::SCHEME_LOOP, o));
    if (!r) fail("OpenSubdiv refused the mesh");
    return r;
}

template <typename R>
static void write(std::string const& path, std::vector<Vertex<R> > const& v, size_t n) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) fail("cannot write " + path);
    for (size_t i = 0; i < n; ++i)
        std::fprintf(f, "%.17g %.17g %.17g\n", (double)v[i].p[0], (double)v[i].p[1], (double)v[i].p[2]);
    if (std::fclose(f) != 0) fail("cannot write " + path);
}

template <typename R>
static void eval(Mesh const& m, Sdc::Options::VtxBoundaryInterpolation b, int levels,
                 std::string const& out) {
    std::vector<int> counts;
    int nv = (int)(m.pos.size() / 3);
    std::vector<Vertex<R> > base(nv);
    for (int i = 0; i < nv; ++i)
        for (int k = 0; k < 3; ++k) base[i].p[k] = (R)m.pos[3 * i + k];
    {
        Far::TopologyRefiner* r = refiner(m, counts, b);
        std::vector<Vertex<R> > lim(nv);
        Far::PrimvarRefinerReal<R>(*r).Limit(base, lim);
        write(out + ".limit", lim, nv);
        delete r;
    }
    Far::TopologyRefiner* r = refiner(m, counts, b);
    r->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
    Far::PrimvarRefinerReal<R> pr(*r);
    std::vector<Vertex<R> > src = base;
    for (int k = 1; k <= levels; ++k) {
        std::vector<Vertex<R> > dst(r->GetLevel(k).GetNumVertices());
        pr.Interpolate(k, src, dst);
        write(out + "." + std::to_string(k), dst, dst.size());
        src.swap(dst);
    }
    delete r;
}

static void bench(Mesh const& m, Sdc::Options::VtxBoundaryInterpolation b, int levels, int reps) {
    int nv = (int)(m.pos.size() / 3);
    std::vector<Vertex<float> > base(nv);
    for (int i = 0; i < nv; ++i)
        for (int k = 0; k < 3; ++k) base[i].p[k] = (float)m.pos[3 * i + k];
    for (int level = 1; level <= levels; ++level) {
        double best = 1e30;
        size_t out = 0;
        for (int rep = 0; rep < reps; ++rep) {
            auto t0 = std::chrono::steady_clock::now();
            std::vector<int> counts;
            Far::TopologyRefiner* r = refiner(m, counts, b);
            r->RefineUniform(Far::TopologyRefiner::UniformOptions(level));
            Far::PrimvarRefiner pr(*r);
            std::vector<Vertex<float> > src = base, dst;
            for (int k = 1; k <= level; ++k) {
                dst.resize(r->GetLevel(k).GetNumVertices());
                pr.Interpolate(k, src, dst);
                src.swap(dst);
            }
            double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            if (s < best) best = s;
            out = src.size();
            delete r;
        }
        std::printf("%d %zu %.9f\n", level, out, best);
    }
}

int main(int argc, char** argv) {
    if (argc < 2) fail("usage: osd_loop eval RULE REAL IN.obj LEVELS OUT | bench RULE IN.obj LEVELS REPS");
    std::string mode = argv[1];
    if (mode == "eval" && argc == 7) {
        Mesh m = read_obj(argv[4]);
        std::string real = argv[3];
        if (real == "float")
            eval<float>(m, rule(argv[2]), std::atoi(argv[5]), argv[6]);
        else if (real == "double")
            eval<double>(m, rule(argv[2]), std::atoi(argv[5]), argv[6]);
        else
            fail("REAL is float or double");
        return 0;
    }
    if (mode == "bench" && argc == 6) {
        Mesh m = read_obj(argv[3]);
        bench(m, rule(argv[2]), std::atoi(argv[4]), std::atoi(argv[5]));
        return 0;
    }
    fail("usage: osd_loop eval RULE REAL IN.obj LEVELS OUT | bench RULE IN.obj LEVELS REPS");
    return 2;
}
