// Works out, once, what drives each target joint (docs/retargeting.md, "How it works"):
// - pairs: a source and a target joint that map to the same H-Anim joint;
// - spans: the source joints whose rotations a target joint's segment stands for. A target joint covers the source
//   from below its parent's span down to the deepest of (its own H-Anim joint's lowest source joint, the joint where
//   the source's paths to the target's next paired joints part). So the humanoid's one-joint torso (vl5) follows
//   the source's whole back (lowerback .. thorax), and a joint no pair lies below follows nothing (rest pose);
// - runs: a target joint and the unpaired joints below it that cover the same span share its source path; each
//   takes the source's rotation change at its place along the chord, blended between the two nearest source joints
//   (a spine of 3 onto a spine of 5);
// - rest alignment: the rotation turning the target's rest bone onto the source's rest bone, so rest poses that
//   differ (T-pose, A-pose, CMU's splayed legs) are reconciled.
#include <osgActor/core/retarget/RetargetRig>
#include <osgActor/core/retarget/HAnimHumanoid>
#include <osgActor/core/retarget/JointMapGuess>
#include <osgActor/core/retarget/JointRotationFit>
#include <osgActor/core/ik/IkKinematics>

#include "ModelMatrices.h"
#include "RotationColumns.h"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace osgActor {

glm::dvec3 RetargetRig::mapPosition(const glm::dvec3& sourcePoint) const
{
    const glm::dvec3 up(0.0, 0.0, 1.0);
    return _alignment * (_scale * (sourcePoint - _sourceFloor * up)) + _targetFloor * up;
}

namespace {

/** One side of the rig while it is built. */
struct Side
{
    const char* label; // "source", "target"
    ActorDefinitionPtr definition;
    std::vector<double> rest;
    std::vector<int> hanim;     // per joint
    std::vector<int> topOf;                // per H-Anim joint: its first joint, or -1
    std::vector<std::vector<int>> runOf;   // per H-Anim joint: its joints, top first (one line of descent)
    std::vector<glm::dmat4> restModels;
    std::vector<std::vector<unsigned>> children;

    glm::dvec3 position(int joint) const { return glm::dvec3(restModels[static_cast<unsigned>(joint)][3]); }
    glm::dmat3 rotation(int joint) const { return glm::dmat3(restModels[static_cast<unsigned>(joint)]); }
    int parent(int joint) const { return definition->getParent(static_cast<unsigned>(joint)); }
    bool isAncestorOrSelf(int ancestor, int joint) const
    {
        for (int j = joint; j >= 0; j = parent(j))
            if (j == ancestor) return true;
        return false;
    }
    int top(const char* hanimName) const { return topOf[static_cast<unsigned>(findHAnimJoint(hanimName))]; }
};

/** Checks one side's definition, rest pose and map; fills the side or returns the message. */
std::string prepareSide(const RetargetSkeleton& skeleton, Side& side, std::vector<std::string>& notes)
{
    const std::string label = side.label;
    if (!skeleton.definition) return "the " + label + " has no skeleton";
    const ActorDefinition& definition = *skeleton.definition;
    side.definition = skeleton.definition;
    side.rest = skeleton.restDofs.empty() ? definition.getDefaultDofs() : skeleton.restDofs;
    if (side.rest.size() != definition.getNumDofs())
        return "the " + label + " rest pose has " + std::to_string(side.rest.size()) + " values, but skeleton '" +
               definition.getName() + "' has " + std::to_string(definition.getNumDofs()) + " DOFs";
    for (unsigned d = 0; d < side.rest.size(); ++d)
        if (!std::isfinite(side.rest[d]) || std::abs(side.rest[d]) > kMaxDofMagnitude)
        {
            std::ostringstream value;
            value << side.rest[d];
            return "the " + label + " rest pose gives DOF '" + definition.getDofName(d) + "' of skeleton '" +
                   definition.getName() + "' the value " + value.str() + ", not a finite number";
        }

    JointMap map = skeleton.map;
    if (map.empty())
    {
        const JointMapGuess guess = guessJointMap(definition, side.rest);
        map = guess.map;
        notes.push_back(label + " '" + definition.getName() + "': " + describeJointMapGuess(guess));
    }
    const JointMapResolveResult resolved = resolveJointMap(map, definition);
    if (!resolved) return "the " + label + " skeleton '" + definition.getName() + "': " + resolved.error;
    side.hanim = resolved.map.hanimOfJoint;
    for (const std::string& dropped : resolved.map.dropped) notes.push_back(label + " map entry dropped: " + dropped);

    const unsigned numJoints = definition.getNumJoints();
    side.topOf.assign(getNumHAnimJoints(), -1);
    side.runOf.assign(getNumHAnimJoints(), {});
    side.children.assign(numJoints, {});
    side.restModels = retarget_detail::computeModelMatrices(definition, side.rest);
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const int parent = definition.getParent(j);
        if (parent >= 0) side.children[static_cast<unsigned>(parent)].push_back(j);
        const int h = side.hanim[j];
        if (h < 0) continue;
        if (side.topOf[static_cast<unsigned>(h)] < 0) side.topOf[static_cast<unsigned>(h)] = static_cast<int>(j);
        side.runOf[static_cast<unsigned>(h)].push_back(static_cast<int>(j)); // parents first: later is deeper
    }
    return std::string();
}

/** Left-to-right (lateral), forward and up (+Z) of a side at rest, from its hips (else shoulders, else ankles); false
  * when it has no such pair. */
bool bodyFrame(const Side& side, glm::dmat3& frame)
{
    static const char* const kPairs[][2] = {{"l_hip", "r_hip"}, {"l_shoulder", "r_shoulder"}, {"l_ankle", "r_ankle"}};
    for (const auto& pair : kPairs)
    {
        const int left = side.top(pair[0]), right = side.top(pair[1]);
        if (left < 0 || right < 0) continue;
        glm::dvec3 lateral = side.position(left) - side.position(right);
        lateral.z = 0.0;
        const double length = glm::length(lateral);
        if (!(length > 1e-9)) continue;
        lateral /= length;
        const glm::dvec3 up(0.0, 0.0, 1.0);
        frame = glm::dmat3(lateral, glm::cross(lateral, up), up);
        return true;
    }
    return false;
}

/** How high HumanoidRoot stands above the ankles with the legs straight: its height above the hips at rest plus the
  * thigh's and the shank's lengths (the mean of both legs), so legs splayed or bent at rest (CMU's are splayed by
  * 20 degrees) do not shorten it. Without legs, its height above the lowest joint at rest; 0 without a HumanoidRoot. */
double hipHeight(const Side& side)
{
    const int root = side.top("HumanoidRoot");
    if (root < 0) return 0.0;
    static const char* const kLegs[][3] = {{"l_hip", "l_knee", "l_ankle"}, {"r_hip", "r_knee", "r_ankle"}};
    double sum = 0.0;
    unsigned legs = 0;
    for (const auto& leg : kLegs)
    {
        const int hip = side.top(leg[0]), knee = side.top(leg[1]), ankle = side.top(leg[2]);
        if (hip < 0 || knee < 0 || ankle < 0) continue;
        sum += side.position(root).z - side.position(hip).z + glm::length(side.position(knee) - side.position(hip)) +
               glm::length(side.position(ankle) - side.position(knee));
        ++legs;
    }
    if (legs > 0) return sum / legs;
    double lowest = side.position(root).z;
    for (const glm::dmat4& model : side.restModels) lowest = std::min(lowest, model[3].z);
    return side.position(root).z - lowest;
}

int lowestCommonAncestor(const Side& side, int a, int b)
{
    for (int x = a; x >= 0; x = side.parent(x))
        if (side.isAncestorOrSelf(x, b)) return x;
    return -1;
}

glm::dvec3 centroid(const Side& side, const std::vector<int>& joints)
{
    glm::dvec3 sum(0.0);
    for (int j : joints) sum += side.position(j);
    return sum / static_cast<double>(joints.size());
}

bool nearIdentity(const glm::dmat3& m)
{
    for (unsigned c = 0; c < 3; ++c)
        for (unsigned r = 0; r < 3; ++r)
            if (std::abs(m[c][r] - (c == r ? 1.0 : 0.0)) > 1e-12) return false;
    return true;
}

} // namespace

/** Builds the rig's tables; a friend of RetargetRig. */
struct RetargetRigBuilder
{
    const RetargetOptions& options;
    Side source{"source", {}, {}, {}, {}, {}, {}, {}};
    Side target{"target", {}, {}, {}, {}, {}, {}, {}};
    std::shared_ptr<RetargetRig> rig;

    // Per target joint.
    std::vector<int> effectiveHAnim; // its H-Anim joint if the source has it too, else -1
    // The source joint it pairs with: where both sides have as many joints of its H-Anim joint, the one at the same
    // place in that line; otherwise the first joint of the source's line, for the first of the target's, and -1 for
    // the others (twins: they move with the first).
    std::vector<int> partner;
    std::vector<int> ownSpan; // the deepest source joint of its own pairing, or -1
    std::vector<bool> twin;
    std::vector<std::vector<int>> frontier; // nearest paired joints below, of another H-Anim joint
    std::vector<int> span;                  // B: the deepest source joint its segment covers, or -1
    std::vector<int> runTop;  // the first joint of its run, or -1
    std::vector<int> twinOf;  // the joint above of the same H-Anim joint, or -1

    explicit RetargetRigBuilder(const RetargetOptions& o) : options(o) {}

    bool paired(unsigned t) const { return effectiveHAnim[t] >= 0; }
    /** Paired and not a twin: a joint whose partner starts a span of its own. */
    bool anchors(unsigned t) const { return paired(t) && !twin[t]; }

    std::string build(const RetargetSkeleton& sourceSkeleton, const RetargetSkeleton& targetSkeleton)
    {
        rig.reset(new RetargetRig);
        std::string error = prepareSide(sourceSkeleton, source, rig->_notes);
        if (error.empty()) error = prepareSide(targetSkeleton, target, rig->_notes);
        if (!error.empty()) return error;

        const unsigned numTarget = target.definition->getNumJoints();
        effectiveHAnim.assign(numTarget, -1);
        partner.assign(numTarget, -1);
        ownSpan.assign(numTarget, -1);
        twin.assign(numTarget, false);
        std::vector<unsigned> seen(getNumHAnimJoints(), 0);
        unsigned numPaired = 0;
        for (unsigned t = 0; t < numTarget; ++t)
        {
            const int h = target.hanim[t];
            if (h < 0 || source.runOf[static_cast<unsigned>(h)].empty()) continue;
            const std::vector<int>& sourceRun = source.runOf[static_cast<unsigned>(h)];
            const unsigned place = seen[static_cast<unsigned>(h)]++;
            effectiveHAnim[t] = h;
            ++numPaired;
            if (sourceRun.size() == target.runOf[static_cast<unsigned>(h)].size())
                partner[t] = ownSpan[t] = sourceRun[place];
            else if (place == 0)
            {
                partner[t] = sourceRun.front();
                ownSpan[t] = sourceRun.back();
            }
            else
                twin[t] = true;
        }
        if (numPaired == 0)
            return "the source skeleton '" + source.definition->getName() + "' and the target skeleton '" +
                   target.definition->getName() + "' have no H-Anim joint in common (" +
                   std::to_string(countMapped(source)) + " and " + std::to_string(countMapped(target)) +
                   " joints mapped)";

        alignAndScale();
        findSpans();
        planRuns();
        findCopies();
        finish();
        return std::string();
    }

    static unsigned countMapped(const Side& side)
    {
        return static_cast<unsigned>(std::count_if(side.hanim.begin(), side.hanim.end(), [](int h) { return h >= 0; }));
    }

    void alignAndScale()
    {
        glm::dmat3 sourceFrame, targetFrame;
        if (bodyFrame(source, sourceFrame) && bodyFrame(target, targetFrame))
            rig->_alignment = targetFrame * glm::transpose(sourceFrame);
        else
            rig->_notes.push_back("no left and right hips, shoulders or ankles on both skeletons: their facings are "
                                  "taken to agree");
        rig->_alignmentIsIdentity = nearIdentity(rig->_alignment);
        if (rig->_alignmentIsIdentity) rig->_alignment = glm::dmat3(1.0);
        rig->_sourceHipHeight = hipHeight(source);
        rig->_targetHipHeight = hipHeight(target);
        if (options.scale > 0.0)
            rig->_scale = options.scale;
        else if (rig->_sourceHipHeight > 0.0 && rig->_targetHipHeight > 0.0)
            rig->_scale = rig->_targetHipHeight / rig->_sourceHipHeight;
        else
        {
            rig->_scale = 1.0;
            rig->_notes.push_back("no hip height on both skeletons: positions are carried over at scale 1");
        }
        rig->_sourceFloor = options.sourceFloor;
        rig->_targetFloor = options.targetFloor;
    }

    /** frontier and span (B) of every target joint. */
    void findSpans()
    {
        const unsigned numTarget = target.definition->getNumJoints();
        frontier.assign(numTarget, {});
        for (unsigned t = numTarget; t-- > 0;)
            for (unsigned child : target.children[t])
            {
                if (anchors(child))
                    frontier[t].push_back(static_cast<int>(child));
                else
                    frontier[t].insert(frontier[t].end(), frontier[child].begin(), frontier[child].end());
            }
        span.assign(numTarget, -1);
        for (unsigned t = 0; t < numTarget; ++t)
        {
            // Where the source's paths to the frontier's partners part: the common ancestor of their parents.
            int parting = -1;
            bool first = true;
            for (int f : frontier[t])
            {
                const int above = source.parent(partner[static_cast<unsigned>(f)]);
                if (above < 0)
                {
                    parting = -1; // a partner is the source's root: nothing above it to follow
                    break;
                }
                parting = first ? above : lowestCommonAncestor(source, parting, above);
                first = false;
                if (parting < 0) break;
            }
            if (twin[t])
            {
                span[t] = span[static_cast<unsigned>(target.parent(static_cast<int>(t)))];
                continue;
            }
            const int own = ownSpan[t];
            if (own >= 0 && parting >= 0)
                span[t] = source.isAncestorOrSelf(own, parting) ? parting : own;
            else
                span[t] = own >= 0 ? own : parting;
        }
    }

    /** Groups target joints into runs and gives each its blend of source joints and its rest alignment. */
    void planRuns()
    {
        const unsigned numTarget = target.definition->getNumJoints();
        rig->_plans.assign(numTarget, RetargetJointPlan());
        runTop.assign(numTarget, -1);
        twinOf.assign(numTarget, -1);
        const int targetRoot = target.top("HumanoidRoot");
        for (unsigned t = 0; t < numTarget; ++t)
        {
            const int parent = target.parent(static_cast<int>(t));
            if (span[t] < 0) continue; // Rest
            if (twin[t])
            {
                twinOf[t] = parent; // planned after its run, below
                runTop[t] = runTop[static_cast<unsigned>(parent)];
                continue;
            }
            if (parent >= 0 && !paired(t) && span[t] == span[static_cast<unsigned>(parent)])
            {
                runTop[t] = runTop[static_cast<unsigned>(parent)];
                continue; // planned with its run's top, below
            }
            runTop[t] = static_cast<int>(t);
        }
        for (unsigned t = 0; t < numTarget; ++t)
            if (runTop[t] == static_cast<int>(t)) planRun(t, static_cast<int>(t) == targetRoot);
        // A second joint of the same H-Anim joint (a twist bone) moves with the first, as one bone.
        for (unsigned t = 0; t < numTarget; ++t)
            if (twinOf[t] >= 0) rig->_plans[t] = rig->_plans[static_cast<unsigned>(twinOf[t])];
        // Rotations after the runs: postRotation needs each joint's final blend and alignment.
        for (unsigned t = 0; t < numTarget; ++t)
        {
            RetargetJointPlan& plan = rig->_plans[t];
            if (plan.kind == RetargetJointKind::Rest) continue;
            const glm::dmat3 alignedRest = glm::transpose(rig->_alignment) * plan.restAlignment *
                                           target.rotation(static_cast<int>(t));
            plan.postRotation = plan.weight == 1.0 && plan.sourceB >= 0
                                    ? glm::transpose(source.rotation(plan.sourceB)) * alignedRest
                                    : alignedRest;
            plan.postIsIdentity = nearIdentity(plan.postRotation);
            if (plan.postIsIdentity) plan.postRotation = glm::dmat3(1.0);
        }
    }

    /** The end of a joint's segment at rest on one side: the centroid of the given joints, else of its children. */
    static bool segmentEnd(const Side& side, int joint, const std::vector<int>& ends, glm::dvec3& end)
    {
        if (!ends.empty())
        {
            end = centroid(side, ends);
            return true;
        }
        const auto& children = side.children[static_cast<unsigned>(joint)];
        if (children.empty()) return false;
        end = centroid(side, std::vector<int>(children.begin(), children.end()));
        return true;
    }

    void planRun(unsigned top, bool isTargetRoot)
    {
        const unsigned numTarget = target.definition->getNumJoints();
        std::vector<unsigned> members;
        for (unsigned t = top; t < numTarget; ++t)
            if (runTop[t] == static_cast<int>(top) && twinOf[t] < 0) members.push_back(t);
        const int parent = target.parent(static_cast<int>(top));
        const int B = span[top];
        const int P = parent >= 0 ? span[static_cast<unsigned>(parent)] : -1;

        // The source path: below P down to B (B alone when P is not above it).
        std::vector<int> path;
        if (P != B)
        {
            for (int s = B; s >= 0 && s != P; s = source.parent(s)) path.push_back(s);
            if (P >= 0 && !source.isAncestorOrSelf(P, B)) path.assign(1, B);
            std::reverse(path.begin(), path.end());
        }

        // Rest alignment: the target's chord onto the source's.
        glm::dmat3 alignment(1.0);
        const glm::dmat3 parentAlignment =
            parent >= 0 ? rig->_plans[static_cast<unsigned>(parent)].restAlignment : glm::dmat3(1.0);
        std::vector<int> partners;
        for (int f : frontier[top])
            partners.push_back(partner[static_cast<unsigned>(f)]);
        glm::dvec3 targetEnd(0.0), sourceEnd(0.0);
        const bool hasTargetEnd = segmentEnd(target, static_cast<int>(top), frontier[top], targetEnd);
        const int sourceStart = anchors(top) ? partner[top]
                                            : (path.empty() ? B : path.front());
        const bool hasSourceEnd = segmentEnd(source, B, partners, sourceEnd);
        if (isTargetRoot)
            alignment = glm::dmat3(1.0);
        else if (path.empty() || !hasTargetEnd || !hasSourceEnd)
            alignment = parentAlignment;
        else
        {
            const glm::dvec3 targetChord = targetEnd - target.position(static_cast<int>(top));
            const glm::dvec3 sourceChord = rig->_alignment * (sourceEnd - source.position(sourceStart));
            const double scale = std::max(glm::length(targetChord), glm::length(sourceChord));
            alignment = glm::length(targetChord) > 1e-9 * scale && glm::length(sourceChord) > 1e-9 * scale
                            ? shortestArc(targetChord, sourceChord)
                            : parentAlignment;
        }

        // Along the source chord: u of each path joint's segment end; along the target's: v of each member's.
        std::vector<double> u(path.size() + 1, 0.0);
        if (!path.empty())
        {
            const glm::dvec3 origin = source.position(path.front());
            const glm::dvec3 chord = (hasSourceEnd ? sourceEnd : source.position(path.back())) - origin;
            const double chord2 = glm::dot(chord, chord);
            for (std::size_t i = 0; i < path.size(); ++i)
            {
                const glm::dvec3 end = i + 1 < path.size() ? source.position(path[i + 1]) : origin + chord;
                const double along = chord2 > 0.0 ? glm::dot(end - origin, chord) / chord2 : 1.0;
                u[i + 1] = i + 1 == path.size() ? 1.0 : std::min(1.0, std::max(u[i], along));
            }
        }
        for (unsigned t : members)
        {
            RetargetJointPlan& plan = rig->_plans[t];
            plan.kind = RetargetJointKind::Follow;
            plan.restAlignment = alignment;
            if (path.empty())
            {
                // Covers what its parent covers: moves with it.
                plan.sourceA = -1;
                plan.sourceB = B;
                plan.weight = 1.0;
                continue;
            }
            const double v = memberPlace(top, t);
            std::size_t i = 1;
            while (i < path.size() && u[i] < v) ++i;
            const double span01 = u[i] - u[i - 1];
            double w = span01 > 0.0 ? (v - u[i - 1]) / span01 : 1.0;
            w = std::min(1.0, std::max(0.0, w));
            plan.sourceB = path[i - 1];
            // Before the path's first joint: the parent's span; for a skeleton root, which has none, the first
            // joint's own (so HumanoidRoot turns with the source's, whatever a zero-length joint below it does).
            plan.sourceA = i >= 2 ? path[i - 2] : (P >= 0 ? P : path.front());
            plan.weight = w;
            if (w > 1.0 - 1e-9)
            {
                plan.weight = 1.0;
                plan.sourceA = -1;
            }
            else if ((w < 1e-9 && plan.sourceA >= 0) || plan.sourceA == plan.sourceB)
            {
                plan.sourceB = plan.sourceA;
                plan.sourceA = -1;
                plan.weight = 1.0;
            }
        }
    }

    /** Where a run member's segment ends along the run's chord (0 at the top's joint, 1 at the run's end). */
    double memberPlace(unsigned top, unsigned member) const
    {
        glm::dvec3 end;
        if (!segmentEnd(target, static_cast<int>(member), frontier[member], end)) return 1.0;
        // The segment ends at the member's next joint in the run, else at the run's end.
        for (unsigned child : target.children[member])
            if (runTop[child] == static_cast<int>(top) && !frontier[child].empty())
            {
                end = target.position(static_cast<int>(child));
                break;
            }
        glm::dvec3 runEnd;
        if (!segmentEnd(target, static_cast<int>(member), frontier[member], runEnd)) return 1.0;
        const glm::dvec3 origin = target.position(static_cast<int>(top));
        const glm::dvec3 chord = runEnd - origin;
        const double chord2 = glm::dot(chord, chord);
        if (!(chord2 > 0.0)) return 1.0;
        return std::min(1.0, std::max(0.0, glm::dot(end - origin, chord) / chord2));
    }

    /** Joints whose local frames are their source partner's: their angles are copied (the same skeleton). */
    void findCopies()
    {
        const ActorDefinition& s = *source.definition;
        const ActorDefinition& t = *target.definition;
        for (unsigned j = 0; j < t.getNumJoints(); ++j)
        {
            RetargetJointPlan& plan = rig->_plans[j];
            if (plan.kind != RetargetJointKind::Follow || plan.weight != 1.0 || plan.sourceB < 0) continue;
            const unsigned b = static_cast<unsigned>(plan.sourceB);
            const int targetParent = t.getParent(j), sourceParent = s.getParent(b);
            const glm::dmat3 targetOffset = glm::mat3_cast(t.getOffsetRotation(j));
            const glm::dmat3 sourceOffset = glm::mat3_cast(s.getOffsetRotation(b));
            glm::dmat3 conjugation;
            if (targetParent < 0 && sourceParent < 0)
                conjugation = glm::transpose(targetOffset) * rig->_alignment * sourceOffset;
            else if (targetParent >= 0 && sourceParent >= 0 &&
                     rig->_plans[static_cast<unsigned>(targetParent)].kind != RetargetJointKind::Rest &&
                     rig->_plans[static_cast<unsigned>(targetParent)].sourceB == sourceParent &&
                     rig->_plans[static_cast<unsigned>(targetParent)].weight == 1.0)
                conjugation = glm::transpose(targetOffset) *
                              glm::transpose(rig->_plans[static_cast<unsigned>(targetParent)].postRotation) *
                              sourceOffset;
            else
                continue;
            const JointKinematics& tk = t.getKinematics(j);
            const JointKinematics& sk = s.getKinematics(b);
            if (!nearIdentity(conjugation) || !plan.postIsIdentity || tk.numRotations != sk.numRotations)
                continue;
            if (!std::equal(tk.rotationAxis, tk.rotationAxis + tk.numRotations, sk.rotationAxis)) continue;
            plan.kind = RetargetJointKind::Copy;
        }
    }

    void finish()
    {
        rig->_source = source.definition;
        rig->_target = target.definition;
        rig->_sourceRest = source.rest;
        rig->_targetRest = target.rest;
        rig->_sourceHAnim = source.hanim;
        rig->_targetHAnim = target.hanim;
        rig->_sourceTopOf = source.topOf;
        rig->_targetTopOf = target.topOf;
        rig->_sourceRestModels = source.restModels;
        rig->_targetRestModels = target.restModels;
        for (unsigned j = 0; j < source.definition->getNumJoints(); ++j)
            rig->_sourceOffsets.push_back(glm::mat3_cast(source.definition->getOffsetRotation(j)));
        for (unsigned j = 0; j < target.definition->getNumJoints(); ++j)
        {
            rig->_targetOffsets.push_back(glm::mat3_cast(target.definition->getOffsetRotation(j)));
            rig->_targetRestLocals.push_back(rig->_targetOffsets.back() *
                                             jointRotation(target.definition->getKinematics(j), target.rest.data()));
        }
        rig->_sourceRoot = source.top("HumanoidRoot");
        rig->_targetRoot = target.top("HumanoidRoot");
        if (rig->_sourceRoot < 0 || rig->_targetRoot < 0)
            rig->_notes.push_back("no HumanoidRoot on both skeletons: the root's travel is not carried over");
        else if (!target.definition->getKinematics(static_cast<unsigned>(rig->_targetRoot)).hasTranslation)
            rig->_notes.push_back("target root '" +
                                  target.definition->getJointName(static_cast<unsigned>(rig->_targetRoot)) +
                                  "' has no translation DOF: the root's travel is dropped");
        std::string rest;
        for (unsigned t = 0; t < rig->_plans.size(); ++t)
            if (rig->_plans[t].kind == RetargetJointKind::Rest &&
                target.definition->getNumJointDofs(t) > 0)
                rest += (rest.empty() ? "" : ", ") + target.definition->getJointName(t);
        if (!rest.empty()) rig->_notes.push_back("target joints no source joint drives (kept at rest): " + rest);
        buildJobTables();
    }

    /** RetargetJobTables: the rig's rotations as columns of four, the constant origins, the Euler and copy batches. */
    void buildJobTables()
    {
        using retarget_detail::kRotationDoubles;
        using retarget_detail::storeRotation;
        const ActorDefinition& t = *target.definition;
        const unsigned numTarget = t.getNumJoints();
        RetargetJobTables& tables = rig->_jobTables;
        storeRotation(tables.alignment, rig->_alignment);
        tables.postRotations.resize(std::size_t(numTarget) * kRotationDoubles);
        tables.offsetRotations.resize(std::size_t(numTarget) * kRotationDoubles);
        tables.restLocalRotations.resize(std::size_t(numTarget) * kRotationDoubles);
        tables.offsetIsIdentity.assign(numTarget, 0);
        tables.origins.assign(std::size_t(numTarget) * 4, 0.0);
        tables.originMoves.assign(numTarget, 0);
        tables.inEulerBatch.assign(numTarget, 0);
        tables.translationTriples.clear();
        tables.translationDofs.clear();
        markSourceJointsRead(tables.sourceJointsRead);
        const unsigned numSource = source.definition->getNumJoints();
        tables.sourcePosed.clear();
        tables.sourcePosedParents.clear();
        for (unsigned j = 0; j < numSource; ++j)
            if (tables.sourceJointsRead[j]) tables.sourcePosed.push_back(j);
        tables.sourceSlots.assign(numSource, static_cast<std::uint32_t>(tables.sourcePosed.size()));
        for (std::size_t i = 0; i < tables.sourcePosed.size(); ++i)
        {
            const int parent = source.parent(static_cast<int>(tables.sourcePosed[i]));
            tables.sourceSlots[tables.sourcePosed[i]] = static_cast<std::uint32_t>(i);
            // Read joints' ancestors are read: the parent has its place already.
            tables.sourcePosedParents.push_back(parent < 0 ? -1
                                                           : static_cast<int>(tables.sourceSlots[static_cast<unsigned>(parent)]));
        }
        planSourcePose(tables);
        tables.desire.assign(numTarget, RetargetDesire::FromPlan);
        tables.desireSlot.assign(numTarget, 0);
        for (unsigned j = 0; j < numTarget; ++j)
        {
            const RetargetJointPlan& plan = rig->_plans[j];
            if (plan.kind == RetargetJointKind::Rest)
                tables.desire[j] = RetargetDesire::Rest;
            else if (plan.weight == 1.0 && plan.sourceB >= 0)
            {
                tables.desire[j] = plan.postIsIdentity ? RetargetDesire::Follow : RetargetDesire::FollowThenPost;
                tables.desireSlot[j] = tables.sourceSlots[static_cast<unsigned>(plan.sourceB)];
            }
        }
        // Each posed source joint's first Follow or FollowThenPost target joint takes its desired rotation from the
        // forward kinematics; a second one following the same source joint is left to the desire pass.
        tables.desireJoints.clear();
        for (unsigned j = 0; j < numTarget; ++j)
        {
            const RetargetDesire desire = tables.desire[j];
            if (desire == RetargetDesire::Follow || desire == RetargetDesire::FollowThenPost)
            {
                RetargetSourceJoint& followed = tables.sourceJoints[tables.desireSlot[j]];
                if (followed.follower == RetargetSourceJoint::kNoFollower)
                {
                    followed.follower = j;
                    followed.followerTurns = desire == RetargetDesire::FollowThenPost ? 1 : 0;
                    continue;
                }
            }
            tables.desireJoints.push_back(j);
        }
        for (unsigned j = 0; j < numTarget; ++j)
        {
            storeRotation(&tables.postRotations[j * kRotationDoubles], rig->_plans[j].postRotation);
            storeRotation(&tables.offsetRotations[j * kRotationDoubles], rig->_targetOffsets[j]);
            storeRotation(&tables.restLocalRotations[j * kRotationDoubles], rig->_targetRestLocals[j]);
            tables.offsetIsIdentity[j] = rig->_targetOffsets[j] == glm::dmat3(1.0) ? 1 : 0;
            const JointKinematics& k = t.getKinematics(j);
            const std::int32_t* const slides = k.translationDof;
            if (slides[0] >= 0 && slides[1] == slides[0] + 1 && slides[2] == slides[0] + 2)
                tables.translationTriples.push_back(static_cast<std::uint32_t>(slides[0]));
            else
                for (unsigned axis = 0; axis < 3; ++axis)
                    if (slides[axis] >= 0) tables.translationDofs.push_back(static_cast<std::uint32_t>(slides[axis]));
            const bool carriesTravel = static_cast<int>(j) == rig->_targetRoot && rig->_sourceRoot >= 0;
            tables.originMoves[j] =
                k.hasTranslation && (carriesTravel || k.translationMode == TranslationMode::AfterRotation) ? 1 : 0;
            glm::dvec3 origin(k.offset[3]);
            if (k.hasTranslation && !tables.originMoves[j])
                origin += rig->_targetOffsets[j] * jointSlide(k, target.rest.data());
            for (unsigned axis = 0; axis < 3; ++axis) tables.origins[4 * j + axis] = origin[axis];
        }

        planPlacement(tables);
        for (unsigned j = 0; j < numTarget; ++j)
        {
            const JointKinematics& k = t.getKinematics(j);
            if (rig->_plans[j].kind != RetargetJointKind::Follow || k.numRotations != 3) continue;
            if (tables.eulerBatches.empty() ||
                tables.eulerBatches.back().numJoints == RetargetEulerBatch::kWidth)
                tables.eulerBatches.emplace_back();
            RetargetEulerBatch& batch = tables.eulerBatches.back();
            tables.inEulerBatch[j] = 1;
            // Lanes past the last joint repeat it until another joint takes them.
            for (unsigned lane = batch.numJoints; lane < RetargetEulerBatch::kWidth; ++lane)
                setEulerLane(batch, lane, j);
            ++batch.numJoints;
        }
        tables.copyBatches.clear();
        for (unsigned j = 0; j < numTarget; ++j)
        {
            // A joint with no rotation has nothing to take.
            if (rig->_plans[j].kind != RetargetJointKind::Copy || t.getKinematics(j).numRotations == 0) continue;
            if (tables.copyBatches.empty() || tables.copyBatches.back().numJoints == RetargetCopyBatch::kWidth)
                tables.copyBatches.emplace_back();
            RetargetCopyBatch& batch = tables.copyBatches.back();
            // Lanes past the last joint repeat it until another joint takes them.
            for (unsigned lane = batch.numJoints; lane < RetargetCopyBatch::kWidth; ++lane) setCopyLane(batch, lane, j);
            ++batch.numJoints;
        }
        // A joint in no Euler or copy batch reads the slot after the last batch's, which stays 0 (its lanes never stand).
        tables.laneAt.assign(numTarget,
                             static_cast<std::uint32_t>(16 * (tables.eulerBatches.size() + tables.copyBatches.size())));
        std::uint32_t batchIndex = 0;
        for (const RetargetEulerBatch& batch : tables.eulerBatches)
        {
            for (unsigned lane = 0; lane < batch.numJoints; ++lane) tables.laneAt[batch.joints[lane]] = 16 * batchIndex + lane;
            ++batchIndex;
        }
        for (const RetargetCopyBatch& batch : tables.copyBatches)
        {
            for (unsigned lane = 0; lane < batch.numJoints; ++lane) tables.laneAt[batch.joints[lane]] = 16 * batchIndex + lane;
            ++batchIndex;
        }
        for (std::uint32_t b = 0; b < tables.axisBatches.size(); ++b)
        {
            const RetargetAxisBatch& batch = tables.axisBatches[b];
            for (unsigned lane = 0; lane < batch.numJoints; ++lane) tables.laneAt[batch.joints[lane]] = 32 * b + lane;
        }
        tables.placement.resize(numTarget);
        for (unsigned j = 0; j < numTarget; ++j)
        {
            const RetargetJointKind kind = rig->_plans[j].kind;
            tables.placement[j] = kind == RetargetJointKind::Rest   ? RetargetPlacement::Rest
                                  : kind == RetargetJointKind::Copy ? RetargetPlacement::Copy
                                  : tables.inEulerBatch[j]          ? RetargetPlacement::Euler
                                  : tables.inAxisBatch[j]           ? RetargetPlacement::Axis
                                                                    : RetargetPlacement::Fit;
        }
    }

    /** RetargetJobTables::sourceJoints and sourceAngleColumns, for the posed source joints (sourcePosed). Each angle a
      * posed joint turns by lies in a column of four consecutive DOFs, the columns laid down from the lowest such DOF
      * up (the last one moved down so it ends at the last DOF). */
    void planSourcePose(RetargetJobTables& tables) const
    {
        const ActorDefinition& s = *source.definition;
        const unsigned numDofs = s.getNumDofs();
        std::vector<std::uint8_t> turns(numDofs, 0);
        for (const std::uint32_t j : tables.sourcePosed)
        {
            const JointKinematics& k = s.getKinematics(j);
            for (unsigned r = 0; r < k.numRotations; ++r) turns[k.rotationDof[r]] = 1;
        }
        // Per DOF, where its sine and cosine go: 4 c + its place in column c.
        std::vector<std::uint32_t> trigOf(numDofs, 0);
        tables.sourceAngleColumns.clear();
        for (unsigned dof = 0; dof < numDofs; ++dof)
        {
            if (!turns[dof]) continue;
            const std::uint32_t first = numDofs < 4 ? 0 : std::min(dof, numDofs - 4);
            const std::uint32_t column = static_cast<std::uint32_t>(tables.sourceAngleColumns.size());
            tables.sourceAngleColumns.push_back(first);
            for (unsigned d = dof; d < std::min(first + 4, numDofs); ++d) trigOf[d] = 4 * column + (d - first);
            dof = first + 3;
        }
        tables.sourceJoints.assign(tables.sourcePosed.size(), RetargetSourceJoint{});
        tables.sourceRuns.clear();
        for (std::size_t i = 0; i < tables.sourcePosed.size(); ++i)
        {
            const JointKinematics& k = s.getKinematics(tables.sourcePosed[i]);
            RetargetSourceJoint& joint = tables.sourceJoints[i];
            joint.parent = tables.sourcePosedParents[i];
            joint.turnsOnly = k.offsetIsTranslation && !k.hasTranslation ? 1 : 0;
            for (unsigned c = 0; c < 4; ++c) joint.offset[c] = k.offset[3][c];
            for (unsigned r = 0; r < k.numRotations; ++r) joint.trig[r] = trigOf[k.rotationDof[r]];
            const std::uint8_t sequence = joint.turnsOnly ? static_cast<std::uint8_t>(k.rotationSequence) : 0;
            if (tables.sourceRuns.empty() || tables.sourceRuns.back().turnsOnly != joint.turnsOnly ||
                tables.sourceRuns.back().rotationSequence != sequence)
            {
                RetargetSourceRun run;
                run.first = static_cast<std::uint32_t>(i);
                run.turnsOnly = joint.turnsOnly;
                run.rotationSequence = sequence;
                tables.sourceRuns.push_back(run);
            }
            tables.sourceRuns.back().end = static_cast<std::uint32_t>(i + 1);
        }
    }

    /** A lane of a copy batch for target joint j (its plan a Copy of source joint sourceB). */
    void setCopyLane(RetargetCopyBatch& batch, unsigned lane, unsigned joint) const
    {
        const ActorDefinition& t = *target.definition;
        const JointKinematics& k = t.getKinematics(joint);
        const JointKinematics& sk = source.definition->getKinematics(static_cast<unsigned>(rig->_plans[joint].sourceB));
        batch.joints[lane] = joint;
        for (unsigned r = 0; r < 3; ++r)
        {
            const bool used = r < k.numRotations;
            batch.sourceDof[r][lane] = used ? sk.rotationDof[r] : sk.rotationDof[0];
            batch.min[r][lane] = used ? t.getDofRangeMin(k.rotationDof[r]) : -std::numeric_limits<double>::infinity();
            batch.max[r][lane] = used ? t.getDofRangeMax(k.rotationDof[r]) : std::numeric_limits<double>::infinity();
        }
    }

    /** RetargetJobTables' placement order by depth and its axis batches. */
    void planPlacement(RetargetJobTables& tables) const
    {
        const ActorDefinition& t = *target.definition;
        const unsigned numTarget = t.getNumJoints();
        std::vector<unsigned> depth(numTarget, 0);
        unsigned numLevels = 0;
        for (unsigned j = 0; j < numTarget; ++j)
        {
            const int parent = t.getParent(j);
            depth[j] = parent < 0 ? 0 : depth[static_cast<unsigned>(parent)] + 1;
            numLevels = std::max(numLevels, depth[j] + 1);
        }
        tables.placeOrder.clear();
        tables.levelJoints.assign(1, 0);
        tables.levelBatches.assign(1, 0);
        tables.axisBatches.clear();
        tables.inAxisBatch.assign(numTarget, 0);
        for (unsigned level = 0; level < numLevels; ++level)
        {
            for (unsigned numRotations = 1; numRotations <= 2; ++numRotations)
            {
                RetargetAxisBatch* batch = nullptr;
                for (unsigned j = 0; j < numTarget; ++j)
                {
                    if (depth[j] != level || rig->_plans[j].kind != RetargetJointKind::Follow ||
                        t.getKinematics(j).numRotations != numRotations)
                        continue;
                    if (!batch || batch->numJoints == RetargetAxisBatch::kWidth)
                    {
                        tables.axisBatches.emplace_back();
                        batch = &tables.axisBatches.back();
                        batch->numRotations = static_cast<std::uint8_t>(numRotations);
                    }
                    tables.inAxisBatch[j] = 1;
                    // Lanes past the last joint repeat it until another joint takes them.
                    for (unsigned lane = batch->numJoints; lane < RetargetAxisBatch::kWidth; ++lane)
                        setAxisLane(*batch, lane, j);
                    ++batch->numJoints;
                }
            }
            for (unsigned j = 0; j < numTarget; ++j)
                if (depth[j] == level) tables.placeOrder.push_back(j);
            tables.levelJoints.push_back(static_cast<std::uint32_t>(tables.placeOrder.size()));
            tables.levelBatches.push_back(static_cast<std::uint32_t>(tables.axisBatches.size()));
        }
    }

    /** A lane of an axis batch for target joint j (one or two rotations). */
    void setAxisLane(RetargetAxisBatch& batch, unsigned lane, unsigned joint) const
    {
        const ActorDefinition& t = *target.definition;
        const JointKinematics& k = t.getKinematics(joint);
        unsigned axes[3];
        axes[0] = k.rotationAxis[0];
        axes[1] = k.numRotations == 2 ? k.rotationAxis[1] : (axes[0] + 1) % 3;
        axes[2] = 3 - axes[0] - axes[1];
        batch.joints[lane] = joint;
        for (unsigned row = 0; row < 3; ++row)
            for (unsigned column = 0; column < 3; ++column)
                batch.element[row][column][lane] = static_cast<std::uint8_t>(4 * axes[column] + axes[row]);
        batch.parity[lane] = axes[1] == (axes[0] + 1) % 3 ? 1.0 : -1.0;
        for (unsigned r = 0; r < k.numRotations; ++r)
        {
            const unsigned dof = k.rotationDof[r];
            batch.dof[r][lane] = dof;
            batch.min[r][lane] = t.getDofRangeMin(dof);
            batch.max[r][lane] = t.getDofRangeMax(dof);
        }
    }

    /** RetargetJobTables::sourceJointsRead. */
    void markSourceJointsRead(std::vector<std::uint8_t>& read) const
    {
        const unsigned numSource = source.definition->getNumJoints();
        read.assign(numSource, 0);
        const auto mark = [&](int joint) {
            if (joint >= 0) read[static_cast<unsigned>(joint)] = 1;
        };
        for (const RetargetJointPlan& plan : rig->_plans)
        {
            if (plan.kind == RetargetJointKind::Rest) continue;
            mark(plan.sourceA);
            mark(plan.sourceB);
        }
        mark(rig->_sourceRoot);
        for (unsigned h = 0; h < getNumHAnimJoints(); ++h)
            if (target.topOf[h] >= 0) mark(source.topOf[h]);
        // Children after their parents: from the last joint up, each read joint marks its parent.
        for (unsigned j = numSource; j-- > 0;)
            if (read[j]) mark(source.parent(static_cast<int>(j)));
    }

    /** A lane of a batch for target joint j (three rotations, distinct axes i, j, k in product order). */
    void setEulerLane(RetargetEulerBatch& batch, unsigned lane, unsigned joint) const
    {
        const ActorDefinition& t = *target.definition;
        const JointKinematics& k = t.getKinematics(joint);
        const unsigned i = k.rotationAxis[0], j = k.rotationAxis[1];
        batch.joints[lane] = joint;
        for (unsigned r = 0; r < 3; ++r) batch.columnAt[r][lane] = static_cast<std::uint8_t>(4 * k.rotationAxis[r]);
        batch.parity[lane] = j == (i + 1) % 3 ? 1.0 : -1.0;
        for (unsigned r = 0; r < 3; ++r)
        {
            const unsigned dof = k.rotationDof[r];
            batch.dof[r][lane] = dof;
            batch.min[r][lane] = t.getDofRangeMin(dof);
            batch.max[r][lane] = t.getDofRangeMax(dof);
        }
    }
};

RetargetRigBuildResult buildRetargetRig(const RetargetSkeleton& source, const RetargetSkeleton& target,
                                        const RetargetOptions& options)
{
    RetargetRigBuildResult result;
    if (!(options.scale >= 0.0) || !std::isfinite(options.scale) || !std::isfinite(options.sourceFloor) ||
        !std::isfinite(options.targetFloor))
    {
        result.error = "retarget options: the scale must be a finite number >= 0 and the floors finite";
        return result;
    }
    RetargetRigBuilder builder(options);
    result.error = builder.build(source, target);
    if (result.error.empty()) result.rig = builder.rig;
    return result;
}

} // namespace osgActor
