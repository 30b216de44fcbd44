#include <osgActor/core/ik/IkSolve>
#include <osgActor/core/ik/CcdIkJob>
#include <osgActor/core/ik/DlsIkJob>
#include <osgActor/core/ik/TwoBoneIkJob>

namespace osgActor {

namespace {

template <class Solver>
bool runAs(IkJob& job)
{
    Solver solver;
    static_cast<IkJob&>(solver) = job;
    const bool ran = solver.run();
    job.result = solver.result;
    return ran;
}

} // namespace

bool solveIk(IkJob& job)
{
    if (!job.chain)
    {
        job.result = IkResult();
        return false;
    }
    switch (job.chain->getSolver())
    {
    case IkSolverType::TwoBone: return runAs<TwoBoneIkJob>(job);
    case IkSolverType::Ccd: return runAs<CcdIkJob>(job);
    case IkSolverType::Dls: return runAs<DlsIkJob>(job);
    }
    return false;
}

} // namespace osgActor
