// He & Liu's analytic Franka Panda IK in C++ (`franka_IK_EE`: all solutions, up to four,
// for one q7) on the poses of `benches/ik_closed_form.rs`, for a same-machine figure next
// to the 0.73 µs. Outside CI and not built by cargo; the header is not in this
// repository: take `franka_ik_He.hpp` from He & Liu's `franka_analytical_ik` repository.
//
//     cargo run --release --example panda_ik_json > /tmp/panda.json
//     python3 benches/panda_ik/panda_ik_bench.py /tmp/panda.json --export-cpp /tmp/panda.txt
//     g++ -std=c++17 -O3 -DNDEBUG -I/usr/include/eigen3 -I DIR_OF_THE_HEADER \
//         benches/panda_ik/he_liu_bench.cpp -o /tmp/he_liu_bench
//     /tmp/he_liu_bench /tmp/panda.txt /tmp/he_liu.txt
//     python3 benches/panda_ik/panda_ik_bench.py /tmp/panda.json --cpp-solutions /tmp/he_liu.txt
//
// It writes every answer (4 rows of 7 per pose, NaN for none) for the script to judge by
// kinegen's fk, then times the 1 000 calls per round (`--rounds`, default 200; median per
// call), q7 of the generating configuration, q_actual = Franka's home configuration.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "franka_ik_He.hpp"

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: he_liu_bench POSES SOLUTIONS_OUT [ROUNDS]\n");
        return 2;
    }
    std::FILE* in = std::fopen(argv[1], "r");
    if (!in) {
        std::perror(argv[1]);
        return 1;
    }
    std::vector<std::array<double, 16>> poses;
    std::vector<double> q7s;
    double q7;
    while (std::fscanf(in, "%lf", &q7) == 1) {
        std::array<double, 16> m;
        for (double& x : m)
            if (std::fscanf(in, "%lf", &x) != 1) return 1;
        poses.push_back(m);
        q7s.push_back(q7);
    }
    std::fclose(in);
    const std::array<double, 7> home = {{0.0, -M_PI_4, 0.0, -3 * M_PI_4, 0.0, M_PI_2, M_PI_4}};
    std::FILE* out = std::fopen(argv[2], "w");
    for (size_t i = 0; i < poses.size(); i++)
        for (const auto& row : franka_IK_EE(poses[i], q7s[i], home)) {
            for (double x : row) std::fprintf(out, "%.17g ", x);
            std::fprintf(out, "\n");
        }
    std::fclose(out);
    const int rounds = argc > 3 ? std::atoi(argv[3]) : 200;
    std::vector<double> per_call;
    volatile double sink = 0;
    for (int r = 0; r < rounds; r++) {
        double acc = 0;
        const auto t0 = std::chrono::steady_clock::now();
        for (size_t i = 0; i < poses.size(); i++) acc += franka_IK_EE(poses[i], q7s[i], home)[0][3];
        const auto t1 = std::chrono::steady_clock::now();
        sink = sink + acc;
        per_call.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / poses.size());
    }
    std::sort(per_call.begin(), per_call.end());
    std::printf("He & Liu franka_IK_EE (C++): median %.3f us per call (min %.3f, max %.3f) over %d rounds of %zu calls\n",
                per_call[per_call.size() / 2] / 1e3, per_call.front() / 1e3, per_call.back() / 1e3, rounds,
                poses.size());
}
