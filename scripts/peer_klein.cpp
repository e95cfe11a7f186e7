// Runs klein's exp of a line (bivector) and log of a motor on the 3D PGA cases that
// scripts/peer_versors.py sends on standard input; built and run by that script.
//
// klein is header-only C++ (SSE, single precision). Its headers come from the crates.io
// package klein-sys, which vendors them (the script fetches it with cargo).
//
// Input, one case a line: `id a b c d e f`, the line a e01 + b e02 + c e03 + d e23 + e e31
// + f e12 in klein's basis (e0 the null vector), as doubles; klein rounds them to float.
// Output, one line per case:
//   `case id exp s e23 e31 e12 e01 e02 e03 e0123 log e01 e02 e03 e23 e31 e12 us t_exp t_log`
// and a first line `overhead t` (the sum of two lines), times in microseconds per call.

#include <klein/klein.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
// Keeps the compiler from dropping a computation whose result is otherwise unused.
template <typename T> inline void keep(T const& value)
{
    asm volatile("" : : "m"(value) : "memory");
}

// Best of 5 repeats of a loop sized to take at least 20 ms, in microseconds per call.
template <typename F> double best_time(F f)
{
    using clock = std::chrono::steady_clock;
    long n      = 1;
    for (;;)
    {
        auto t0 = clock::now();
        for (long i = 0; i < n; ++i)
        {
            f();
        }
        double dt = std::chrono::duration<double, std::micro>(clock::now() - t0).count();
        if (dt >= 20000.0 || n >= (1L << 30))
        {
            break;
        }
        n *= 2;
    }
    double best = 1e300;
    for (int k = 0; k < 5; ++k)
    {
        auto t0 = clock::now();
        for (long i = 0; i < n; ++i)
        {
            f();
        }
        double dt = std::chrono::duration<double, std::micro>(clock::now() - t0).count();
        best      = std::min(best, dt / static_cast<double>(n));
    }
    return best;
}
} // namespace

int main()
{
    kln::line x{-1.3f, 0.8f, -2.1f, 0.6f, 0.7f, 0.4f};
    kln::line y{0.f, 0.f, 0.f, 0.3f, -0.2f, 0.1f};
    double overhead = best_time([&] {
        keep(x);
        kln::line s = x + y;
        keep(s);
    });
    std::printf("overhead %.6g\n", overhead);

    std::string text;
    while (std::getline(std::cin, text))
    {
        std::istringstream in(text);
        std::string id;
        double c[6];
        if (!(in >> id >> c[0] >> c[1] >> c[2] >> c[3] >> c[4] >> c[5]))
        {
            continue;
        }
        kln::line b{static_cast<float>(c[0]),
                    static_cast<float>(c[1]),
                    static_cast<float>(c[2]),
                    static_cast<float>(c[3]),
                    static_cast<float>(c[4]),
                    static_cast<float>(c[5])};
        kln::motor m = kln::exp(b);
        kln::line l  = kln::log(m);
        double t_exp = best_time([&] {
            keep(b);
            kln::motor r = kln::exp(b);
            keep(r);
        });
        double t_log = best_time([&] {
            keep(m);
            kln::line r = kln::log(m);
            keep(r);
        });
        std::printf(
            "case %s exp %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g log %.9g %.9g %.9g %.9g %.9g "
            "%.9g us %.6g %.6g\n",
            id.c_str(),
            m.scalar(), m.e23(), m.e31(), m.e12(), m.e01(), m.e02(), m.e03(), m.e0123(),
            l.e01(), l.e02(), l.e03(), l.e23(), l.e31(), l.e12(),
            t_exp, t_log);
    }
    return 0;
}
