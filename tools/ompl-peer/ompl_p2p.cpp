// ompl_p2p: the OMPL peer of `smug p2p`.
//
// Reads a map_server map (YAML + PGM) and a queries CSV (`sx,sy,syaw,gx,gy,gyaw`, a
// header row allowed), plans every query in order with ONE
// ompl::geometric::LazyPRMstar instance (the roadmap is kept across queries:
// clearQuery() between queries, never clear()) for a disc robot of radius R, and
// writes results JSON in the format of `smug p2p`:
//   {"queries":[{"status","cost","time_s","vertices","waypoints"},...],"total_time_s",
//    "planner":{...}}
//
// Validity is that of SMUG's `clearance-2d` checker: the disc must lie inside the map
// and its (open) interior must not intersect any blocked grid square; a blocked square
// is an occupied or unknown pixel (trinary map_server semantics). Motions are checked
// by OMPL's DiscreteMotionValidator at a fixed planar resolution (default 0.05 m, the
// `smug p2p` default of its `discrete` motion validator).
//
// Build: see build.sh / Makefile. Usage: ompl_p2p --help.

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/config.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace
{
[[noreturn]] void fail(const std::string &message)
{
    std::cerr << "ompl_p2p: " << message << std::endl;
    std::exit(2);
}

std::string trim(const std::string &s)
{
    const char *ws = " \t\r\n";
    const auto a = s.find_first_not_of(ws);
    if (a == std::string::npos)
        return "";
    const auto b = s.find_last_not_of(ws);
    return s.substr(a, b - a + 1);
}

std::string strip_quotes(const std::string &s)
{
    if (s.size() >= 2 && ((s.front() == '"' && s.back() == '"') || (s.front() == '\'' && s.back() == '\'')))
        return s.substr(1, s.size() - 2);
    return s;
}

double parse_double(const std::string &text, const std::string &what)
{
    try
    {
        std::size_t used = 0;
        const double v = std::stod(text, &used);
        if (trim(text.substr(used)).empty())
            return v;
    }
    catch (const std::exception &)
    {
    }
    fail(what + ": expected a number, got `" + text + "`");
}

// ---------------------------------------------------------------------------------
// Map: map_server YAML + PGM (P2/P5, 8 or 16 bit).
// ---------------------------------------------------------------------------------

struct Map
{
    double resolution = 0.0;
    double origin[2] = {0.0, 0.0};
    int nx = 0, ny = 0;
    // blocked[j * nx + i]: grid row j = 0 at the bottom (smallest y).
    std::vector<unsigned char> blocked;

    double max_x() const { return origin[0] + nx * resolution; }
    double max_y() const { return origin[1] + ny * resolution; }
    bool is_blocked(int i, int j) const { return blocked[static_cast<std::size_t>(j) * nx + i] != 0; }
};

struct Pgm
{
    int width = 0, height = 0;
    unsigned max = 255;
    std::vector<unsigned> samples;  // top row first
};

Pgm read_pgm(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(path + ": cannot read image");
    std::string magic;
    in >> magic;
    if (magic != "P5" && magic != "P2")
        fail(path + ": not a PGM (P2/P5) image (only PGM is supported)");
    auto next_int = [&](const char *what) {
        for (;;)
        {
            in >> std::ws;
            if (in.peek() == '#')
            {
                std::string comment;
                std::getline(in, comment);
                continue;
            }
            long v = -1;
            if (!(in >> v) || v < 0)
                fail(path + ": bad PGM header (" + what + ")");
            return v;
        }
    };
    Pgm pgm;
    pgm.width = static_cast<int>(next_int("width"));
    pgm.height = static_cast<int>(next_int("height"));
    const long maxval = next_int("maxval");
    if (pgm.width <= 0 || pgm.height <= 0 || maxval <= 0 || maxval > 65535)
        fail(path + ": bad PGM header values");
    pgm.max = static_cast<unsigned>(maxval);
    const std::size_t n = static_cast<std::size_t>(pgm.width) * pgm.height;
    pgm.samples.resize(n);
    if (magic == "P5")
    {
        in.get();  // the single whitespace after maxval
        const int bytes = maxval > 255 ? 2 : 1;
        std::vector<unsigned char> raw(n * bytes);
        if (!in.read(reinterpret_cast<char *>(raw.data()), static_cast<std::streamsize>(raw.size())))
            fail(path + ": truncated PGM data");
        for (std::size_t k = 0; k < n; ++k)
            pgm.samples[k] = bytes == 2 ? (unsigned(raw[2 * k]) << 8) | raw[2 * k + 1] : raw[k];
    }
    else
    {
        for (std::size_t k = 0; k < n; ++k)
        {
            long v;
            if (!(in >> v) || v < 0)
                fail(path + ": truncated PGM data");
            pgm.samples[k] = static_cast<unsigned>(v);
        }
    }
    return pgm;
}

// The keys SMUG's map files use (`smug worlds convert-movingai` / `export`): image,
// resolution, origin, occupied_thresh, free_thresh, negate, mode. Other keys (SMUG's
// elevation / traversability / mission extensions) are ignored with a warning.
Map read_map(const std::string &yaml_path)
{
    std::ifstream in(yaml_path);
    if (!in)
        fail(yaml_path + ": cannot read map");
    std::string image, mode = "trinary";
    double resolution = -1, occupied = 0.65, free_thresh = 0.196;
    double origin[3] = {0, 0, 0};
    bool have_origin = false, negate = false;
    std::string line;
    int line_no = 0;
    while (std::getline(in, line))
    {
        ++line_no;
        // Strip a comment: `#` at the start or after whitespace, outside quotes.
        bool quoted = false;
        char quote = 0;
        for (std::size_t k = 0; k < line.size(); ++k)
        {
            const char c = line[k];
            if (quoted)
            {
                if (c == quote)
                    quoted = false;
            }
            else if (c == '"' || c == '\'')
            {
                quoted = true;
                quote = c;
            }
            else if (c == '#' && (k == 0 || line[k - 1] == ' ' || line[k - 1] == '\t'))
            {
                line.resize(k);
                break;
            }
        }
        line = trim(line);
        if (line.empty())
            continue;
        const auto colon = line.find(':');
        if (colon == std::string::npos)
            fail(yaml_path + ":" + std::to_string(line_no) + ": expected `key: value`");
        const std::string key = trim(line.substr(0, colon));
        const std::string value = strip_quotes(trim(line.substr(colon + 1)));
        const std::string where = yaml_path + ":" + std::to_string(line_no) + ": " + key;
        if (key == "image")
            image = value;
        else if (key == "resolution")
            resolution = parse_double(value, where);
        else if (key == "origin")
        {
            std::string v = value;
            if (v.size() < 2 || v.front() != '[' || v.back() != ']')
                fail(where + ": expected [x, y, yaw]");
            std::stringstream items(v.substr(1, v.size() - 2));
            std::string item;
            int k = 0;
            while (std::getline(items, item, ','))
            {
                if (k >= 3)
                    fail(where + ": expected [x, y, yaw]");
                origin[k++] = parse_double(trim(item), where);
            }
            if (k != 3)
                fail(where + ": expected [x, y, yaw]");
            have_origin = true;
        }
        else if (key == "occupied_thresh")
            occupied = parse_double(value, where);
        else if (key == "free_thresh")
            free_thresh = parse_double(value, where);
        else if (key == "negate")
        {
            if (value == "1" || value == "true" || value == "True")
                negate = true;
            else if (value == "0" || value == "false" || value == "False")
                negate = false;
            else
                fail(where + ": expected 0 or 1");
        }
        else if (key == "mode")
        {
            if (value != "trinary" && value != "scale" && value != "raw")
                fail(where + ": expected trinary, scale or raw");
            mode = value;
        }
        else
            std::cerr << "ompl_p2p: " << where << ": key ignored" << std::endl;
    }
    if (image.empty())
        fail(yaml_path + ": `image` is required");
    if (!(resolution > 0 && std::isfinite(resolution)))
        fail(yaml_path + ": `resolution` must be a finite number > 0");
    if (!have_origin)
        fail(yaml_path + ": `origin` is required");
    if (origin[2] != 0.0)
        fail(yaml_path + ": origin yaw must be 0 (rotated maps are not supported)");
    std::string image_path = image;
    if (image.front() != '/')
    {
        const auto slash = yaml_path.find_last_of('/');
        if (slash != std::string::npos)
            image_path = yaml_path.substr(0, slash + 1) + image;
    }
    const Pgm pgm = read_pgm(image_path);
    Map map;
    map.resolution = resolution;
    map.origin[0] = origin[0];
    map.origin[1] = origin[1];
    map.nx = pgm.width;
    map.ny = pgm.height;
    map.blocked.assign(static_cast<std::size_t>(map.nx) * map.ny, 0);
    for (int row = 0; row < pgm.height; ++row)
        for (int i = 0; i < pgm.width; ++i)
        {
            double value = double(pgm.samples[static_cast<std::size_t>(row) * pgm.width + i]) / pgm.max;
            if (negate)
                value = 1.0 - value;
            double p;
            bool unknown = false;
            if (mode == "raw")
            {
                const double percent = std::round(value * 255.0);
                unknown = percent > 100.0;
                p = percent / 100.0;
            }
            else
                p = 1.0 - value;
            bool free_cell;
            if (unknown)
                free_cell = false;
            else if (p > occupied)
                free_cell = false;
            else if (p < free_thresh)
                free_cell = true;
            else
                free_cell = mode == "scale";  // between the thresholds: unknown, except in scale mode
            // Image row 0 is the top of the map; grid row 0 the bottom.
            const int j = pgm.height - 1 - row;
            map.blocked[static_cast<std::size_t>(j) * map.nx + i] = free_cell ? 0 : 1;
        }
    return map;
}

// ---------------------------------------------------------------------------------
// Validity: SMUG's clearance-2d semantic, exactly (no distance-field shortcut needed:
// the disc's bounding box covers few cells).
// ---------------------------------------------------------------------------------

struct DiscChecker
{
    const Map *map;
    double radius;

    bool valid(double x, double y) const
    {
        const Map &m = *map;
        const double r = radius, res = m.resolution;
        if (!(x - r >= m.origin[0] && x + r <= m.max_x() && y - r >= m.origin[1] && y + r <= m.max_y()))
            return false;
        // The centre's cell must exist (SMUG's `cell_of`: x == max edge is outside).
        const double fx = (x - m.origin[0]) / res, fy = (y - m.origin[1]) / res;
        if (!(fx >= 0 && fy >= 0) || static_cast<long>(fx) >= m.nx || static_cast<long>(fy) >= m.ny)
            return false;
        auto lo = [&](double v, double o) { return static_cast<long>(std::max(0.0, std::floor((v - r - o) / res))); };
        auto hi = [&](double v, double o, int n) {
            return std::min<long>(static_cast<long>(std::floor((v + r - o) / res)), n - 1);
        };
        for (long j = lo(y, m.origin[1]); j <= hi(y, m.origin[1], m.ny); ++j)
            for (long i = lo(x, m.origin[0]); i <= hi(x, m.origin[0], m.nx); ++i)
            {
                if (!m.is_blocked(static_cast<int>(i), static_cast<int>(j)))
                    continue;
                const double x0 = m.origin[0] + i * res, y0 = m.origin[1] + j * res;
                const double dx = std::max({x0 - x, 0.0, x - (x0 + res)});
                const double dy = std::max({y0 - y, 0.0, y - (y0 + res)});
                if (std::hypot(dx, dy) < r || (r == 0.0 && dx == 0.0 && dy == 0.0))
                    return false;
            }
        return true;
    }
};

// ---------------------------------------------------------------------------------
// Queries CSV, same rules as `smug p2p`.
// ---------------------------------------------------------------------------------

struct Query
{
    double s[3], g[3];
};

std::vector<Query> read_queries(const std::string &path)
{
    std::ifstream in(path);
    if (!in)
        fail(path + ": cannot read");
    std::vector<Query> queries;
    std::string line;
    int n = 0;
    bool first = true;
    while (std::getline(in, line))
    {
        ++n;
        if (trim(line).empty())
            continue;
        std::vector<double> v;
        bool numeric = true;
        std::stringstream fields(line);
        std::string field;
        while (std::getline(fields, field, ','))
        {
            field = trim(field);
            try
            {
                std::size_t used = 0;
                const double x = std::stod(field, &used);
                if (used != field.size())
                    numeric = false;
                v.push_back(x);
            }
            catch (const std::exception &)
            {
                numeric = false;
            }
        }
        const bool is_first = first;
        first = false;
        if (!numeric && is_first && n == 1)
            continue;  // header
        if (!numeric || v.size() != 6 || !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
            fail(path + ":" + std::to_string(n) + ": expected six finite numbers sx,sy,syaw,gx,gy,gyaw, got `" + line +
                 "`");
        queries.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}});
    }
    return queries;
}

// ---------------------------------------------------------------------------------
// JSON output.
// ---------------------------------------------------------------------------------

std::string num(double v)
{
    if (!std::isfinite(v))
        return "null";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

double thread_cpu_s()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Result
{
    std::string status;
    double cost = std::numeric_limits<double>::quiet_NaN();
    double time_s = 0;
    double cpu_s = 0;
    unsigned long vertices = 0;
    std::vector<std::array<double, 3>> waypoints;
};

// SE(2) whose motions are discretised in the plane only. OMPL's
// CompoundStateSpace::validSegmentCount is the max over subspaces, so plain SE(2) would
// split every motion by its heading change too (the SO(2) part gets the same extent
// fraction as R^2, i.e. ~0.05 m / map diagonal of pi rad): thousands of extra checks for
// a heading that weighs nothing and a disc that does not care.
class PlanarSE2 : public ob::SE2StateSpace
{
public:
    unsigned int validSegmentCount(const ob::State *a, const ob::State *b) const override
    {
        return components_[0]->validSegmentCount(a->as<ob::CompoundState>()->components[0],
                                                 b->as<ob::CompoundState>()->components[0]);
    }
};

void usage()
{
    std::cout << "ompl_p2p --map MAP.yaml --queries Q.csv --radius R [--out results.json]\n"
                 "         [--time 0.2] [--seed 1] [--space se2|r2] [--motion-resolution 0.05]\n"
                 "         [--clock wall|cpu] [--first] [--simplify] [--verbose]\n\n"
                 "Plans every query of Q.csv (rows sx,sy,syaw,gx,gy,gyaw in metres, a header row\n"
                 "allowed) in order with one OMPL LazyPRMstar roadmap (clearQuery() between queries)\n"
                 "for a disc robot of radius R (metres) on a map_server map, and writes the results\n"
                 "in the JSON format of `smug p2p`.\n\n"
                 "  --time S               planning time per query, seconds (LazyPRMstar keeps\n"
                 "                         optimising until it runs out)\n"
                 "  --clock wall|cpu       what --time measures: wall-clock time (default, OMPL's\n"
                 "                         timedPlannerTerminationCondition) or this thread's CPU\n"
                 "                         time (steadier on a loaded machine)\n"
                 "  --seed N               ompl::RNG::setSeed(N)\n"
                 "  --space se2            SE(2) with the SO(2) subspace weight 0 (default; same\n"
                 "                         dimension 3, hence the same k-nearest rule, as SMUG)\n"
                 "  --space r2             the plane R^2 (k-nearest rule with d = 2)\n"
                 "  --motion-resolution M  DiscreteMotionValidator step, metres in the plane\n"
                 "                         (SMUG's p2p default: 0.05)\n"
                 "  --first                stop at the first solution (cost threshold = infinity,\n"
                 "                         as plain LazyPRM does) instead of optimising until --time\n"
                 "  --simplify             shortcut + smooth the path with OMPL's PathSimplifier\n"
                 "                         (off by default: SMUG's p2p returns roadmap paths)\n";
}
}  // namespace

int main(int argc, char **argv)
{
    std::string map_path, queries_path, out_path, space_name = "se2", clock_name = "wall";
    double radius = -1, time_per_query = 0.2, motion_resolution = 0.05;
    unsigned long seed = 1;
    bool simplify = false, verbose = false, first = false;
    for (int k = 1; k < argc; ++k)
    {
        const std::string a = argv[k];
        auto value = [&]() -> std::string {
            if (k + 1 >= argc)
                fail(a + " needs a value");
            return argv[++k];
        };
        if (a == "--map")
            map_path = value();
        else if (a == "--queries")
            queries_path = value();
        else if (a == "--out")
            out_path = value();
        else if (a == "--radius")
            radius = parse_double(value(), "--radius");
        else if (a == "--time")
            time_per_query = parse_double(value(), "--time");
        else if (a == "--seed")
            seed = static_cast<unsigned long>(parse_double(value(), "--seed"));
        else if (a == "--space")
            space_name = value();
        else if (a == "--motion-resolution")
            motion_resolution = parse_double(value(), "--motion-resolution");
        else if (a == "--clock")
            clock_name = value();
        else if (a == "--simplify")
            simplify = true;
        else if (a == "--first")
            first = true;
        else if (a == "--verbose")
            verbose = true;
        else if (a == "--help" || a == "-h")
        {
            usage();
            return 0;
        }
        else
            fail("unknown argument `" + a + "` (see --help)");
    }
    if (map_path.empty() || queries_path.empty())
        fail("--map and --queries are required (see --help)");
    if (!(radius >= 0 && std::isfinite(radius)))
        fail("--radius R (metres, >= 0) is required");
    if (!(time_per_query > 0))
        fail("--time must be > 0");
    if (!(motion_resolution > 0))
        fail("--motion-resolution must be > 0");
    if (clock_name != "wall" && clock_name != "cpu")
        fail("--clock must be wall or cpu");
    if (space_name != "se2" && space_name != "r2")
        fail("--space must be se2 or r2");

    // Seed before any OMPL RNG exists (samplers allocate theirs in setup()).
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed));
    ompl::msg::setLogLevel(verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);

    const Map map = read_map(map_path);
    const std::vector<Query> queries = read_queries(queries_path);
    const DiscChecker checker{&map, radius};

    // The state space: the plane, plus (se2) a heading that weighs nothing.
    ob::RealVectorBounds bounds(2);
    bounds.setLow(0, map.origin[0]);
    bounds.setHigh(0, map.max_x());
    bounds.setLow(1, map.origin[1]);
    bounds.setHigh(1, map.max_y());
    ob::StateSpacePtr space;
    std::shared_ptr<PlanarSE2> se2;
    if (space_name == "se2")
    {
        se2 = std::make_shared<PlanarSE2>();
        se2->setBounds(bounds);
        se2->setSubspaceWeight(1, 0.0);  // yaw weight 0: distance = planar distance
        space = se2;
    }
    else
    {
        auto r2 = std::make_shared<ob::RealVectorStateSpace>(2);
        r2->setBounds(bounds);
        space = r2;
    }
    auto si = std::make_shared<ob::SpaceInformation>(space);
    auto xy = [&](const ob::State *s) -> std::array<double, 3> {
        if (se2)
        {
            const auto *st = s->as<ob::SE2StateSpace::StateType>();
            return {st->getX(), st->getY(), st->getYaw()};
        }
        const auto *st = s->as<ob::RealVectorStateSpace::StateType>();
        return {st->values[0], st->values[1], 0.0};
    };
    si->setStateValidityChecker([&](const ob::State *s) {
        const auto p = xy(s);
        return checker.valid(p[0], p[1]);
    });
    // The motion validator: states every `motion_resolution` metres in the plane, checked
    // in bisection order (OMPL's DiscreteMotionValidator; SMUG's `discrete` validator
    // checks the same states, k/n for n = ceil(d / resolution)).
    const double planar_extent = std::hypot(map.max_x() - map.origin[0], map.max_y() - map.origin[1]);
    si->setStateValidityCheckingResolution(motion_resolution / planar_extent);
    si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
    si->setup();

    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
    if (first)
        objective->setCostThreshold(objective->infiniteCost());  // any path satisfies it
    pdef->setOptimizationObjective(objective);
    auto planner = std::make_shared<og::LazyPRMstar>(si);
    planner->setProblemDefinition(pdef);
    planner->setup();
    og::PathSimplifier simplifier(si);

    if (verbose)
    {
        ob::ScopedState<> a(space), b(space);
        a[0] = map.origin[0] + 0.5;
        a[1] = map.origin[1] + 0.5;
        b[0] = a[0] + 1.0;
        b[1] = a[1];
        if (se2)
        {
            a[2] = -3.0;
            b[2] = 3.0;
        }
        std::cerr << "ompl_p2p: " << space_name << ", map " << map.nx << "x" << map.ny << " @ " << map.resolution
                  << " m, distance of a 1 m move = " << si->distance(a.get(), b.get())
                  << ", valid segments = " << space->validSegmentCount(a.get(), b.get()) << std::endl;
    }

    auto set_state = [&](ob::ScopedState<> &st, const double *p) {
        st[0] = p[0];
        st[1] = p[1];
        if (se2)
            st[2] = p[2];
    };

    std::vector<Result> results;
    results.reserve(queries.size());
    const auto all_started = std::chrono::steady_clock::now();
    for (const Query &q : queries)
    {
        const auto started = std::chrono::steady_clock::now();
        const double cpu_started = thread_cpu_s();
        Result r;
        if (!checker.valid(q.s[0], q.s[1]))
            r.status = "invalid_start";
        else if (!checker.valid(q.g[0], q.g[1]))
            r.status = "invalid_goal";
        else
        {
            ob::ScopedState<> start(space), goal(space);
            set_state(start, q.s);
            set_state(goal, q.g);
            pdef->clearSolutionPaths();
            pdef->clearStartStates();
            pdef->clearGoal();
            pdef->setStartAndGoalStates(start, goal);
            planner->clearQuery();  // keep the roadmap, forget the last query
            // LazyPRM checks the condition once per sample; its path repair loop (A*, check,
            // remove, A* again) runs to the end, so a query may overrun the budget.
            const ob::PlannerStatus status = planner->solve(
                clock_name == "wall" ? ob::timedPlannerTerminationCondition(time_per_query) :
                                       ob::PlannerTerminationCondition([cpu_started, time_per_query] {
                                           return thread_cpu_s() - cpu_started >= time_per_query;
                                       }));
            if (status == ob::PlannerStatus::EXACT_SOLUTION || status == ob::PlannerStatus::APPROXIMATE_SOLUTION)
            {
                auto path = pdef->getSolutionPath()->as<og::PathGeometric>();
                og::PathGeometric copy(*path);
                if (simplify)
                    simplifier.simplifyMax(copy);
                double length = 0;
                for (std::size_t k = 0; k < copy.getStateCount(); ++k)
                {
                    auto p = xy(copy.getState(k));
                    if (!se2)
                    {
                        // R^2 has no heading: the query's at the ends, the direction of
                        // travel in between.
                        if (k == 0)
                            p[2] = q.s[2];
                        else if (k + 1 == copy.getStateCount())
                            p[2] = q.g[2];
                        else
                        {
                            const auto n = xy(copy.getState(k + 1));
                            p[2] = std::atan2(n[1] - p[1], n[0] - p[0]);
                        }
                    }
                    if (k > 0)
                    {
                        const auto &prev = r.waypoints.back();
                        length += std::hypot(p[0] - prev[0], p[1] - prev[1]);
                    }
                    r.waypoints.push_back(p);
                }
                const bool exact = status == ob::PlannerStatus::EXACT_SOLUTION;
                r.status = exact ? "exact" : "approximate";
                if (exact)
                    r.cost = length;
            }
            else if (status == ob::PlannerStatus::INVALID_START)
                r.status = "invalid_start";
            else if (status == ob::PlannerStatus::INVALID_GOAL)
                r.status = "invalid_goal";
            else
                r.status = "no_path";
        }
        r.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        r.cpu_s = thread_cpu_s() - cpu_started;
        r.vertices = planner->milestoneCount();
        results.push_back(std::move(r));
    }
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - all_started).count();

    std::size_t exact = 0;
    double cost_sum = 0;
    for (const auto &r : results)
        if (r.status == "exact")
        {
            ++exact;
            cost_sum += r.cost;
        }
    std::printf("%zu queries: %zu exact, %zu without a path; mean cost %.3f; %.3f s; roadmap %lu vertices\n",
                results.size(), exact, results.size() - exact, exact ? cost_sum / exact : 0.0, total,
                planner->milestoneCount());

    if (!out_path.empty())
    {
        std::ofstream out(out_path);
        if (!out)
            fail(out_path + ": cannot write");
        out << "{\n  \"queries\": [";
        for (std::size_t k = 0; k < results.size(); ++k)
        {
            const Result &r = results[k];
            out << (k ? ",\n" : "\n") << "    {\"status\": \"" << r.status << "\", \"cost\": " << num(r.cost)
                << ", \"time_s\": " << num(r.time_s) << ", \"cpu_s\": " << num(r.cpu_s) << ", \"vertices\": " << r.vertices << ", \"waypoints\": [";
            for (std::size_t w = 0; w < r.waypoints.size(); ++w)
                out << (w ? ", " : "") << "[" << num(r.waypoints[w][0]) << ", " << num(r.waypoints[w][1]) << ", "
                    << num(r.waypoints[w][2]) << "]";
            out << "]}";
        }
        out << "\n  ],\n  \"total_time_s\": " << num(total) << ",\n  \"planner\": {\"name\": \"" << planner->getName()
            << "\", \"ompl_version\": \"" << OMPL_MAJOR_VERSION << "." << OMPL_MINOR_VERSION << "."
            << OMPL_PATCH_VERSION << "\", \"space\": \"" << space_name
            << "\", \"time_per_query_s\": " << num(time_per_query) << ", \"clock\": \"" << clock_name << "\"" << ", \"seed\": " << seed
            << ", \"motion_resolution\": " << num(motion_resolution) << ", \"first\": " << (first ? "true" : "false") << ", \"simplify\": "
            << (simplify ? "true" : "false") << ", \"vertices\": " << planner->milestoneCount()
            << ", \"edges\": " << planner->edgeCount() << "}\n}\n";
    }
    return exact == results.size() ? 0 : 1;
}
