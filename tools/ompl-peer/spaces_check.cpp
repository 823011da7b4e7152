// OMPL peer for smug-spaces: reads pose pairs "x1 y1 yaw1 x2 y2 yaw2" (one per line) on
// stdin and prints OMPL's DubinsStateSpace(r).distance and ReedsSheppStateSpace(r).distance
// for each, "dubins rs" per line. Usage: spaces_check RADIUS < pairs.txt
// Built by build.sh beside this file; see SPACES.md.
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/DubinsStateSpace.h>
#include <ompl/base/spaces/ReedsSheppStateSpace.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>

namespace ob = ompl::base;

int main(int argc, char **argv)
{
    if (argc != 2)
    {
        std::fprintf(stderr, "usage: %s RADIUS < pairs\n", argv[0]);
        return 2;
    }
    const double r = std::atof(argv[1]);
    // Default: asymmetric Dubins distance (isSymmetric = false).
    auto dubins = std::make_shared<ob::DubinsStateSpace>(r);
    auto rs = std::make_shared<ob::ReedsSheppStateSpace>(r);
    ob::State *a = dubins->allocState();
    ob::State *b = dubins->allocState();
    double x1, y1, t1, x2, y2, t2;
    while (std::cin >> x1 >> y1 >> t1 >> x2 >> y2 >> t2)
    {
        auto *sa = a->as<ob::SE2StateSpace::StateType>();
        auto *sb = b->as<ob::SE2StateSpace::StateType>();
        sa->setXY(x1, y1);
        sa->setYaw(t1);
        sb->setXY(x2, y2);
        sb->setYaw(t2);
        std::printf("%.17g %.17g\n", dubins->distance(a, b), rs->distance(a, b));
    }
    dubins->freeState(a);
    dubins->freeState(b);
    return 0;
}
