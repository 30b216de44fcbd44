#include <osgActor/core/ik/SweepAcceleration>

#include <algorithm>
#include <cmath>

namespace osgActor {

void SweepHistory::record(const IkChain& chain, const double* start, const double* end, IkWorkspace& workspace)
{
    const unsigned n = chain.getNumDofs();
    if (count == kSweepHistory)
    {
        // Forget the oldest row.
        std::copy(workspace.sweepStarts.begin() + n, workspace.sweepStarts.end(), workspace.sweepStarts.begin());
        std::copy(workspace.sweepEnds.begin() + n, workspace.sweepEnds.end(), workspace.sweepEnds.begin());
        --count;
    }
    std::copy(start, start + n, workspace.sweepStarts.begin() + count * n);
    std::copy(end, end + n, workspace.sweepEnds.begin() + count * n);
    ++count;
}

bool proposeAndersonMix(const IkChain& chain, IkWorkspace& workspace, const SweepHistory& history, double* proposed)
{
    if (history.count < 2) return false;
    const unsigned n = chain.getNumDofs();
    const unsigned m = history.count - 1; // differences to mix
    const unsigned last = m;
    const double* starts = workspace.sweepStarts.data();
    const double* ends = workspace.sweepEnds.data();
    // The residual f_i of DOF d, slides in chain lengths so both kinds weigh alike.
    const double perLength = 1.0 / chain.getLength();
    auto residual = [&](unsigned i, unsigned d) {
        const double f = ends[i * n + d] - starts[i * n + d];
        return isRotation(chain.getDof(d).type) ? f : f * perLength;
    };

    // Least squares min |f_last - dF gamma|, dF's columns f_(i+1) - f_i, by modified Gram-Schmidt (QR without
    // squaring the condition number as the normal equations would). A column that the earlier ones nearly span
    // adds nothing but noise: it is left out (its gamma is 0).
    double* q = workspace.mixingColumns.data(); // column i at q + i * n, orthonormalised in place
    double r[kSweepHistory - 1][kSweepHistory - 1] = {};
    bool used[kSweepHistory - 1] = {};
    double qf[kSweepHistory - 1] = {};
    bool any = false;
    for (unsigned i = 0; i < m; ++i)
    {
        double* column = q + i * n;
        double norm2 = 0.0;
        for (unsigned d = 0; d < n; ++d)
        {
            column[d] = residual(i + 1, d) - residual(i, d);
            norm2 += column[d] * column[d];
        }
        for (unsigned j = 0; j < i; ++j)
        {
            if (!used[j]) continue;
            const double* previous = q + j * n;
            double dot = 0.0;
            for (unsigned d = 0; d < n; ++d) dot += previous[d] * column[d];
            r[j][i] = dot;
            for (unsigned d = 0; d < n; ++d) column[d] -= dot * previous[d];
        }
        double left2 = 0.0;
        for (unsigned d = 0; d < n; ++d) left2 += column[d] * column[d];
        if (!(left2 > 1e-20 * norm2) || !std::isfinite(left2)) continue;
        const double left = std::sqrt(left2);
        r[i][i] = left;
        for (unsigned d = 0; d < n; ++d) column[d] /= left;
        for (unsigned d = 0; d < n; ++d) qf[i] += column[d] * residual(last, d);
        used[i] = any = true;
    }
    if (!any) return false; // the sweeps made no progress to mix
    double gamma[kSweepHistory - 1] = {};
    for (unsigned i = m; i-- > 0;) // R gamma = Q^T f_last over the columns used
    {
        if (!used[i]) continue;
        double value = qf[i];
        for (unsigned k = i + 1; k < m; ++k) value -= r[i][k] * gamma[k];
        gamma[i] = value / r[i][i];
    }

    for (unsigned d = 0; d < n; ++d)
    {
        double value = ends[last * n + d];
        for (unsigned i = 0; i < m; ++i) value -= gamma[i] * (ends[(i + 1) * n + d] - ends[i * n + d]);
        if (!std::isfinite(value)) return false;
        proposed[d] = value;
    }
    return true;
}

void proposePatternMove(const IkChain& chain, const double* start, const double* end, double factor, double* proposed)
{
    for (unsigned d = 0; d < chain.getNumDofs(); ++d) proposed[d] = end[d] + factor * (end[d] - start[d]);
}

} // namespace osgActor
