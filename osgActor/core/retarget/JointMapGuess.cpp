#include <osgActor/core/retarget/JointMapGuess>
#include <osgActor/core/retarget/BuiltInJointMaps>
#include <osgActor/core/retarget/HAnimHumanoid>

#include "ModelMatrices.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

namespace osgActor {

namespace {

// The forearm in proportion to the thigh and shank together (Drillis and Contini's body segment lengths: thigh 0.245,
// shank 0.246, forearm 0.146 of the body's height), and the upper arm to the forearm as rigs draw them (1.0 in
// MakeHuman's, 1.1 in Boxing_Toes.bvh, 1.4 in CMU's; 1.27 in Drillis and Contini's table).
constexpr double kForearmPerLeg = 0.146 / 0.491;
constexpr double kUpperArmPerForearm = 1.15;

/** The joints every humanoid retargeting needs: the guess from names must find them all to be taken. */
const char* const kCoreJoints[] = {"HumanoidRoot", "l_hip",      "r_hip",      "l_knee",  "r_knee",
                                   "l_ankle",      "r_ankle",    "l_shoulder", "r_shoulder", "l_elbow",
                                   "r_elbow",      "l_wrist",    "r_wrist"};

/** A skeleton at rest, with the questions the topology guess asks of it. */
struct RestSkeleton
{
    const ActorDefinition& definition;
    std::vector<glm::dvec3> positions;
    std::vector<std::vector<unsigned>> children;

    RestSkeleton(const ActorDefinition& d, const std::vector<double>& rest) : definition(d)
    {
        const unsigned n = d.getNumJoints();
        const std::vector<glm::dmat4> models = retarget_detail::computeModelMatrices(d, rest);
        positions.resize(n);
        children.resize(n);
        for (unsigned j = 0; j < n; ++j)
        {
            const int parent = d.getParent(j);
            positions[j] = glm::dvec3(models[j][3]);
            if (parent >= 0) children[static_cast<unsigned>(parent)].push_back(j);
        }
    }

    int parent(int j) const { return definition.getParent(static_cast<unsigned>(j)); }
    bool isAncestorOrSelf(int ancestor, int j) const
    {
        for (int x = j; x >= 0; x = parent(x))
            if (x == ancestor) return true;
        return false;
    }
    int commonAncestor(int a, int b) const
    {
        for (int x = a; x >= 0; x = parent(x))
            if (isAncestorOrSelf(x, b)) return x;
        return -1;
    }
    /** The joints from below top (exclusive) down to bottom (inclusive), top first. */
    std::vector<int> pathBelow(int top, int bottom) const
    {
        std::vector<int> path;
        for (int x = bottom; x >= 0 && x != top; x = parent(x)) path.push_back(x);
        std::reverse(path.begin(), path.end());
        return path;
    }
    void leavesBelow(int j, std::vector<int>& leaves) const
    {
        if (children[static_cast<unsigned>(j)].empty()) leaves.push_back(j);
        for (unsigned c : children[static_cast<unsigned>(j)]) leavesBelow(static_cast<int>(c), leaves);
    }
    bool hasDofs(int j) const { return definition.getNumJointDofs(static_cast<unsigned>(j)) > 0; }
    double distance(int a, int b) const { return glm::length(positions[a] - positions[b]); }
};

glm::dvec3 horizontal(const glm::dvec3& v) { return glm::dvec3(v.x, v.y, 0.0); }

/** The path joint (indices first..last of path, inclusive) whose distance from anchor is nearest length; -1 if the
  * range is empty. */
int nearestAtDistance(const RestSkeleton& s, const std::vector<int>& path, int first, int last, int anchor,
                      double length)
{
    int best = -1;
    double bestError = std::numeric_limits<double>::infinity();
    for (int i = first; i <= last; ++i)
    {
        const double error = std::abs(s.distance(path[static_cast<unsigned>(i)], anchor) - length);
        if (error < bestError)
        {
            bestError = error;
            best = i;
        }
    }
    return best;
}

int indexIn(const std::vector<int>& path, int joint)
{
    const auto found = std::find(path.begin(), path.end(), joint);
    return found == path.end() ? -1 : static_cast<int>(found - path.begin());
}

/** The topology guess (see guessJointMap); false and a note when the skeleton has no two legs and a head. */
class TopologyGuess
{
public:
    TopologyGuess(const RestSkeleton& s, JointMapGuess& guess) : _s(s), _guess(guess) {}

    bool run()
    {
        const unsigned n = _s.definition.getNumJoints();
        std::vector<int> leaves;
        for (unsigned j = 0; j < n; ++j)
            if (_s.definition.getParent(j) < 0) _s.leavesBelow(static_cast<int>(j), leaves);
        if (leaves.size() < 3) return fail("fewer than three chain ends: no two legs and a head");
        double zMin = std::numeric_limits<double>::infinity(), zMax = -zMin;
        for (const glm::dvec3& p : _s.positions)
        {
            zMin = std::min(zMin, p.z);
            zMax = std::max(zMax, p.z);
        }
        const double height = zMax - zMin;

        // Feet: the lowest end, and the lowest whose path to it parts well above the feet.
        const int foot1 = *std::min_element(leaves.begin(), leaves.end(), [&](int a, int b) { return z(a) < z(b); });
        int foot2 = -1;
        for (int leaf : leaves)
        {
            const int meet = _s.commonAncestor(foot1, leaf);
            if (leaf == foot1 || meet < 0 || z(meet) < z(foot1) + 0.3 * height) continue;
            if (foot2 < 0 || z(leaf) < z(foot2)) foot2 = leaf;
        }
        if (foot2 < 0) return fail("no second foot: no end low down whose chain parts from the first above the knees");
        const int head = *std::max_element(leaves.begin(), leaves.end(), [&](int a, int b) { return z(a) < z(b); });
        const int feetMeet = _s.commonAncestor(foot1, foot2);
        const int root = _s.commonAncestor(feetMeet, head);
        if (root < 0) return fail("the feet and the head are in separate skeletons");
        set(root, "HumanoidRoot", "where the feet's and the head's chains meet");
        if (feetMeet != root) set(feetMeet, "sacroiliac", "where the two legs part, below HumanoidRoot");

        // Facing: the way the feet point; left is to its left.
        Leg legs[2];
        double legLength = 0.0;
        for (unsigned i = 0; i < 2; ++i)
        {
            if (!findLeg(feetMeet, i == 0 ? foot1 : foot2, legs[i])) return false;
            legLength += 0.5 * (_s.distance(legs[i].hip, legs[i].knee) + _s.distance(legs[i].knee, legs[i].ankle));
        }
        glm::dvec3 forward = horizontal(_s.positions[foot1] - _s.positions[legs[0].ankle]) +
                             horizontal(_s.positions[foot2] - _s.positions[legs[1].ankle]);
        if (!(glm::length(forward) > 1e-9 * height))
        {
            forward = glm::dvec3(0.0, -1.0, 0.0);
            _guess.notes.push_back("the feet do not point forward: facing -Y assumed (osgActor's convention)");
        }
        _left = glm::normalize(glm::cross(glm::dvec3(0.0, 0.0, 1.0), glm::normalize(forward)));
        for (const Leg& leg : legs) placeLeg(leg, feetMeet);

        // Hands: the ends farthest out on either side, away from the legs and the head's chain.
        std::vector<int> arms;
        for (int leaf : leaves)
            if (!_s.isAncestorOrSelf(legs[0].top, leaf) && !_s.isAncestorOrSelf(legs[1].top, leaf) &&
                !_s.isAncestorOrSelf(leaf, head) && _s.isAncestorOrSelf(root, leaf))
                arms.push_back(leaf);
        auto out = [&](int j) { return horizontal(_s.positions[j] - _s.positions[root]); };
        int hand1 = -1, hand2 = -1;
        for (int leaf : arms)
            if (hand1 < 0 || glm::length(out(leaf)) > glm::length(out(hand1))) hand1 = leaf;
        for (int leaf : arms)
            if (hand1 >= 0 && glm::dot(out(leaf), out(hand1)) < 0.0 &&
                (hand2 < 0 || glm::length(out(leaf)) > glm::length(out(hand2))))
                hand2 = leaf;
        int chest = -1;
        if (hand2 < 0)
            _guess.notes.push_back("no two hands on either side of the body: arms not mapped");
        else
        {
            chest = _s.commonAncestor(hand1, hand2);
            if (chest != root) set(chest, "vt6", "where the two arms' chains meet");
            for (int hand : {hand1, hand2}) placeArm(chest, hand, legLength);
        }

        // Spine and neck: only their ends; the joints between are blended along the chain when retargeting.
        const std::vector<int> toChest = chest >= 0 ? _s.pathBelow(root, chest) : std::vector<int>();
        if (toChest.size() >= 2) set(toChest.front(), "vl5", "the first joint of the spine above HumanoidRoot");
        // The head: where the head's chain branches (a face), else its last joint that moves.
        const int neckBase = chest >= 0 ? chest : root;
        int headJoint = _s.hasDofs(head) || _s.parent(head) < 0 ? head : _s.parent(head);
        for (int j : _s.pathBelow(neckBase, head))
            if (_s.children[static_cast<unsigned>(j)].size() > 1)
            {
                headJoint = j;
                break;
            }
        if (headJoint != neckBase && _s.isAncestorOrSelf(neckBase, headJoint))
        {
            set(headJoint, "skullbase", "where the head's chain branches, else its last joint that moves");
            const std::vector<int> neck = _s.pathBelow(neckBase, headJoint);
            if (neck.size() >= 2 && chest >= 0) set(neck.front(), "vc7", "the first joint of the neck");
        }
        return true;
    }

private:
    struct Leg
    {
        int top = -1, hip = -1, knee = -1, ankle = -1, foot = -1;
        std::vector<int> path;
    };

    double z(int j) const { return _s.positions[static_cast<unsigned>(j)].z; }

    bool fail(const std::string& why)
    {
        _guess.notes.push_back("topology: " + why);
        return false;
    }

    void set(int joint, const std::string& hanim, const std::string& why)
    {
        const std::string& name = _s.definition.getJointName(static_cast<unsigned>(joint));
        if (_guess.map.find(name)) return;
        _guess.map.add(name, hanim);
        _guess.notes.push_back(name + " -> " + hanim + ": " + why);
    }

    const char* side(int joint) const
    {
        return glm::dot(_s.positions[static_cast<unsigned>(joint)] - _s.positions[static_cast<unsigned>(_root)],
                        _left) >= 0.0
                   ? "l_"
                   : "r_";
    }

    bool findLeg(int feetMeet, int foot, Leg& leg)
    {
        leg.foot = foot;
        leg.path = _s.pathBelow(feetMeet, foot);
        _root = feetMeet;
        // The joints that may be the ankle: every one that moves (an End Site joint is the foot's tip).
        const int last = static_cast<int>(leg.path.size()) - (_s.hasDofs(foot) ? 1 : 2);
        if (last < 2) return fail("a leg with no knee between the hip and the ankle");
        // Hip: the lowest corner near the top of the leg, where a bone from the pelvis's centre turns into the thigh
        // (a joint with no bone above it counts as one); twist joints down the thigh turn nothing.
        const double top = z(feetMeet), legDrop = z(feetMeet) - z(foot);
        leg.hip = leg.path[0];
        for (int i = 0; i + 2 <= last; ++i)
        {
            if (z(leg.path[i]) < top - 0.25 * legDrop) break;
            const glm::dvec3 in = _s.positions[leg.path[i]] - _s.positions[i > 0 ? leg.path[i - 1] : feetMeet];
            const glm::dvec3 out = _s.positions[leg.path[i + 1]] - _s.positions[leg.path[i]];
            const double inLength = glm::length(in), outLength = glm::length(out);
            if (!(outLength > 0.0)) continue;
            if (!(inLength > 1e-9 * legDrop) || glm::dot(in, out) < std::cos(glm::radians(10.0)) * inLength * outLength)
                leg.hip = leg.path[i];
        }
        // Knee and ankle: thigh and shank are as long as each other, so of the joints below the hip they are the
        // pair with the knee as far from the hip as from the ankle (the joints of the foot below the ankle, and twist
        // joints half way down the shank, upset that balance).
        double best = std::numeric_limits<double>::infinity();
        for (int k = indexIn(leg.path, leg.hip) + 1; k < last; ++k)
            for (int a = k + 1; a <= last; ++a)
            {
                const double upper = _s.distance(leg.hip, leg.path[k]), lower = _s.distance(leg.path[k], leg.path[a]);
                const double imbalance = std::abs(upper - lower) / (upper + lower);
                if (imbalance < best)
                {
                    best = imbalance;
                    leg.knee = leg.path[k];
                    leg.ankle = leg.path[a];
                }
            }
        if (leg.knee < 0) return fail("a leg with no knee between the hip and the ankle");
        leg.top = leg.path.front();
        return true;
    }

    void placeLeg(const Leg& leg, int /*feetMeet*/)
    {
        const std::string s = side(leg.knee);
        const int hipAt = indexIn(leg.path, leg.hip), kneeAt = indexIn(leg.path, leg.knee),
                  ankleAt = indexIn(leg.path, leg.ankle);
        set(leg.hip, s + "hip", "a leg's first joint away from the pelvis");
        set(leg.knee, s + "knee", "as far from the hip as from the ankle");
        set(leg.ankle, s + "ankle", "a shank's length below the knee, as long as the thigh");
        for (int i = hipAt + 1; i < kneeAt; ++i) set(leg.path[i], s + "hip", "a twist bone of the thigh");
        for (int i = kneeAt + 1; i < ankleAt; ++i) set(leg.path[i], s + "knee", "a twist bone of the shank");
        const auto& below = _s.children[static_cast<unsigned>(leg.ankle)];
        if (below.size() == 1 && ankleAt + 1 < static_cast<int>(leg.path.size()) &&
            (_s.hasDofs(static_cast<int>(below[0])) && !_s.children[below[0]].empty()))
            set(static_cast<int>(below[0]), s + "metatarsal", "the foot's one joint below the ankle");
    }

    void placeArm(int chest, int hand, double legLength)
    {
        const std::vector<int> path = _s.pathBelow(chest, hand);
        if (path.empty()) return;
        // Wrist: where the fingers part, else the hand's last joint that moves.
        std::vector<int> ends;
        _s.leavesBelow(path.front(), ends);
        int wrist = ends.front();
        for (int end : ends) wrist = _s.commonAncestor(wrist, end);
        if (ends.size() == 1 && !_s.hasDofs(wrist)) wrist = _s.parent(wrist);
        const int wristAt = indexIn(path, wrist);
        if (wristAt < 2)
        {
            _guess.notes.push_back("an arm too short for a shoulder, an elbow and a wrist: not mapped");
            return;
        }
        const int elbowAt = nearestAtDistance(_s, path, 1, wristAt - 1, wrist, kForearmPerLeg * legLength);
        const int shoulderAt = nearestAtDistance(_s, path, 0, elbowAt - 1, path[elbowAt],
                                                 kUpperArmPerForearm * _s.distance(path[elbowAt], wrist));
        const std::string s = side(path[elbowAt]);
        set(path[shoulderAt], s + "shoulder", "an upper arm's length above the elbow");
        set(path[elbowAt], s + "elbow", "a forearm's length above the wrist");
        set(wrist, s + "wrist", "where the fingers part");
        for (int i = shoulderAt + 1; i < elbowAt; ++i) set(path[i], s + "shoulder", "a twist bone of the upper arm");
        for (int i = elbowAt + 1; i < wristAt; ++i) set(path[i], s + "elbow", "a twist bone of the forearm");
        if (shoulderAt >= 1) set(path[0], s + "sternoclavicular", "the arm's first joint, before the shoulder");
        if (shoulderAt >= 2) set(path[1], s + "acromioclavicular", "the arm's second joint, before the shoulder");
        placeFingers(wrist, s);
    }

    /** Finger joints by their names: the k-th moving joint of a finger's chain is <finger>k (thumb1..3, index1..3). */
    void placeFingers(int wrist, const std::string& s)
    {
        static const char* const kFingers[][2] = {
            {"thumb", "thumb"}, {"index", "index"}, {"middle", "middle"}, {"ring", "ring"},
            {"pinky", "pinky"}, {"little", "pinky"}};
        for (unsigned child : _s.children[static_cast<unsigned>(wrist)])
        {
            std::vector<int> chain;
            for (int j = static_cast<int>(child); j >= 0;)
            {
                if (_s.hasDofs(j)) chain.push_back(j);
                const auto& next = _s.children[static_cast<unsigned>(j)];
                j = next.size() == 1 ? static_cast<int>(next[0]) : -1;
            }
            if (chain.empty()) continue;
            std::string name = _s.definition.getJointName(static_cast<unsigned>(chain.front()));
            std::transform(name.begin(), name.end(), name.begin(),
                           [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
            for (const auto& finger : kFingers)
            {
                if (name.find(finger[0]) == std::string::npos) continue;
                for (std::size_t k = 0; k < chain.size() && k < 3; ++k)
                    set(chain[k], s + finger[1] + std::to_string(k + 1), "a finger joint, by its name");
                break;
            }
        }
    }

    const RestSkeleton& _s;
    JointMapGuess& _guess;
    glm::dvec3 _left{1.0, 0.0, 0.0};
    int _root = -1;
};

/** The built-in map that maps the most joints, with its count and whether it found every core joint. */
struct BuiltInChoice
{
    int style = -1;
    unsigned numMapped = 0;
    bool complete = false;
    std::vector<int> hanimOfJoint;
};

BuiltInChoice bestBuiltInMap(const ActorDefinition& definition)
{
    BuiltInChoice best;
    for (unsigned style = 0; style < kNumJointMapStyles; ++style)
    {
        const JointMapResolveResult resolved =
            resolveJointMap(builtInJointMap(static_cast<JointMapStyle>(style)), definition);
        if (!resolved || resolved.map.numMapped <= best.numMapped) continue;
        best.style = static_cast<int>(style);
        best.numMapped = resolved.map.numMapped;
        best.hanimOfJoint = resolved.map.hanimOfJoint;
        best.complete = true;
        for (const char* core : kCoreJoints)
            if (std::find(best.hanimOfJoint.begin(), best.hanimOfJoint.end(), findHAnimJoint(core)) ==
                best.hanimOfJoint.end())
                best.complete = false;
    }
    return best;
}

} // namespace

JointMapGuess guessJointMap(const ActorDefinition& definition, const std::vector<double>& restDofs)
{
    JointMapGuess guess;
    guess.map.setName("guessed for '" + definition.getName() + "'");
    const BuiltInChoice builtIn = bestBuiltInMap(definition);
    bool found = false;
    if (builtIn.complete)
    {
        guess.method = std::string("built-in map '") + jointMapStyleName(static_cast<JointMapStyle>(builtIn.style)) +
                       "'";
        for (unsigned j = 0; j < definition.getNumJoints(); ++j)
            if (builtIn.hanimOfJoint[j] >= 0)
                guess.map.add(definition.getJointName(j),
                              getHAnimJoint(static_cast<unsigned>(builtIn.hanimOfJoint[j])).name);
        found = true;
    }
    else
    {
        const std::vector<double>& rest =
            restDofs.size() == definition.getNumDofs() ? restDofs : definition.getDefaultDofs();
        const RestSkeleton skeleton(definition, rest);
        guess.method = "topology";
        found = TopologyGuess(skeleton, guess).run();
        if (!found && builtIn.style >= 0)
        {
            // Half a map by names beats none.
            guess.map = JointMap(guess.map.getName());
            guess.method = std::string("built-in map '") +
                           jointMapStyleName(static_cast<JointMapStyle>(builtIn.style)) + "' (incomplete)";
            for (unsigned j = 0; j < definition.getNumJoints(); ++j)
                if (builtIn.hanimOfJoint[j] >= 0)
                    guess.map.add(definition.getJointName(j),
                                  getHAnimJoint(static_cast<unsigned>(builtIn.hanimOfJoint[j])).name);
        }
    }

    // What is missing, and what is left out. A topology guess that contradicts the hierarchy loses the contradicting
    // entries here, as a loose map would.
    JointMap loose = guess.map;
    loose.setLooseMatching(true);
    const JointMapResolveResult resolved = resolveJointMap(loose, definition);
    const std::vector<int> hanimOfJoint =
        resolved ? resolved.map.hanimOfJoint : std::vector<int>(definition.getNumJoints(), -1);
    if (resolved)
        for (const std::string& dropped : resolved.map.dropped) guess.notes.push_back("dropped: " + dropped);
    JointMap exact(guess.map.getName());
    for (unsigned j = 0; j < definition.getNumJoints(); ++j)
    {
        if (hanimOfJoint[j] >= 0)
            exact.add(definition.getJointName(j), getHAnimJoint(static_cast<unsigned>(hanimOfJoint[j])).name);
        else if (definition.getNumJointDofs(j) > 0)
            guess.unmappedJoints.push_back(definition.getJointName(j));
    }
    guess.map = exact;
    for (unsigned h = 0; h < getNumHAnimJoints(); ++h)
        if (getHAnimJoint(h).levelOfArticulation <= 1 &&
            std::find(hanimOfJoint.begin(), hanimOfJoint.end(), static_cast<int>(h)) == hanimOfJoint.end())
            guess.missingHAnim.push_back(getHAnimJoint(h).name);
    (void)found;
    return guess;
}

std::string describeJointMapGuess(const JointMapGuess& guess)
{
    std::string text = "joint map guessed by " + guess.method + ": " +
                       std::to_string(guess.map.getEntries().size()) + " joints mapped";
    auto list = [&text](const char* label, const std::vector<std::string>& names) {
        if (names.empty()) return;
        text += std::string("; ") + label + ": ";
        for (std::size_t i = 0; i < names.size(); ++i) text += (i ? ", " : "") + names[i];
    };
    list("H-Anim level-1 joints not found", guess.missingHAnim);
    list("joints left unmapped", guess.unmappedJoints);
    return text;
}

} // namespace osgActor
