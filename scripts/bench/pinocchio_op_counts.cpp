// Exact operation counts of Pinocchio's recursive algorithms on a robot, by
// running them once on a counting scalar type: the reference column of the
// op-count table in docs/humanoid.md (scripts/bench/op_counts.sh builds and
// runs it).
//
// Usage: pinocchio_op_counts ROBOT.model
//   ROBOT.model: the text form of a Pinocchio model that the peers' harness
//   writes (urdf_model.py ROBOT.urdf [--floating] > ROBOT.model): one line per
//   joint, `kind parent axis(3) R(9) p(3) mass lever(3) I(9)`.
// Output: CSV robot,nv,algo,add,mul,div,sqrt,sincos,other,flops where add
//   counts additions and subtractions (and negations), flops = add + mul + div.
//   Multiplications by structural zeros of Pinocchio's dense spatial blocks are
//   counted: they are the work it does (its SIMD packing is not counted).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

struct Counts {
  static long add, mul, div, sqrt, sincos, other;
};
long Counts::add = 0, Counts::mul = 0, Counts::div = 0, Counts::sqrt = 0, Counts::sincos = 0,
     Counts::other = 0;

// A double that counts every arithmetic operation done on it.
struct C {
  double v = 0.0;
  C() = default;
  C(double x) : v(x) {}
  explicit operator double() const { return v; }
  C& operator+=(const C& b) { ++Counts::add; v += b.v; return *this; }
  C& operator-=(const C& b) { ++Counts::add; v -= b.v; return *this; }
  C& operator*=(const C& b) { ++Counts::mul; v *= b.v; return *this; }
  C& operator/=(const C& b) { ++Counts::div; v /= b.v; return *this; }
};
inline C operator+(const C& a, const C& b) { ++Counts::add; return C(a.v + b.v); }
inline C operator-(const C& a, const C& b) { ++Counts::add; return C(a.v - b.v); }
inline C operator*(const C& a, const C& b) { ++Counts::mul; return C(a.v * b.v); }
inline C operator/(const C& a, const C& b) { ++Counts::div; return C(a.v / b.v); }
inline C operator-(const C& a) { ++Counts::add; return C(-a.v); }
inline C operator+(const C& a) { return a; }
inline bool operator<(const C& a, const C& b) { return a.v < b.v; }
inline bool operator>(const C& a, const C& b) { return a.v > b.v; }
inline bool operator<=(const C& a, const C& b) { return a.v <= b.v; }
inline bool operator>=(const C& a, const C& b) { return a.v >= b.v; }
inline bool operator==(const C& a, const C& b) { return a.v == b.v; }
inline bool operator!=(const C& a, const C& b) { return a.v != b.v; }
inline C sin(const C& a) { ++Counts::sincos; return C(std::sin(a.v)); }
inline C cos(const C& a) { ++Counts::sincos; return C(std::cos(a.v)); }
inline C sqrt(const C& a) { ++Counts::sqrt; return C(std::sqrt(a.v)); }
inline C abs(const C& a) { return C(std::fabs(a.v)); }
inline C fabs(const C& a) { return C(std::fabs(a.v)); }
inline C atan2(const C& a, const C& b) { ++Counts::other; return C(std::atan2(a.v, b.v)); }
inline C acos(const C& a) { ++Counts::other; return C(std::acos(a.v)); }
inline C asin(const C& a) { ++Counts::other; return C(std::asin(a.v)); }
inline C atan(const C& a) { ++Counts::other; return C(std::atan(a.v)); }
inline C exp(const C& a) { ++Counts::other; return C(std::exp(a.v)); }
inline C log(const C& a) { ++Counts::other; return C(std::log(a.v)); }
inline C tan(const C& a) { ++Counts::other; return C(std::tan(a.v)); }
inline C pow(const C& a, const C& b) { ++Counts::other; return C(std::pow(a.v, b.v)); }
inline C floor(const C& a) { return C(std::floor(a.v)); }
inline C ceil(const C& a) { return C(std::ceil(a.v)); }
inline C min(const C& a, const C& b) { return a.v < b.v ? a : b; }
inline C max(const C& a, const C& b) { return a.v < b.v ? b : a; }
inline bool isfinite(const C& a) { return std::isfinite(a.v); }
inline bool isnan(const C& a) { return std::isnan(a.v); }
inline bool isinf(const C& a) { return std::isinf(a.v); }

#include <Eigen/Core>
namespace Eigen {
template <>
struct NumTraits<C> : GenericNumTraits<C> {
  typedef C Real;
  typedef C NonInteger;
  typedef C Literal;
  typedef C Nested;
  enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 1, ReadCost = 1,
         AddCost = 1, MulCost = 1 };
  static inline C epsilon() { return C(std::numeric_limits<double>::epsilon()); }
  static inline C dummy_precision() { return C(1e-12); }
  static inline C highest() { return C(std::numeric_limits<double>::max()); }
  static inline C lowest() { return C(-std::numeric_limits<double>::max()); }
  static inline C infinity() { return C(std::numeric_limits<double>::infinity()); }
  static inline C quiet_NaN() { return C(std::numeric_limits<double>::quiet_NaN()); }
  static inline int digits10() { return 15; }
  static inline int max_digits10() { return 17; }
  static inline int digits() { return 53; }
};
}  // namespace Eigen

#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/joint-configuration.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>

namespace pin = pinocchio;

static void reset() { Counts::add = Counts::mul = Counts::div = Counts::sqrt = Counts::sincos = Counts::other = 0; }

static void report(const std::string& robot, int nv, const char* algo) {
  std::printf("%s,%d,%s,%ld,%ld,%ld,%ld,%ld,%ld,%ld\n", robot.c_str(), nv, algo, Counts::add, Counts::mul,
              Counts::div, Counts::sqrt, Counts::sincos, Counts::other, Counts::add + Counts::mul + Counts::div);
}

int main(int argc, char** argv) {
  if (argc < 2) { std::fprintf(stderr, "usage: pinocchio_op_counts ROBOT.model\n"); return 1; }
  std::string path = argv[1];
  pin::Model model;
  std::ifstream in(path);
  int joints = 0;
  if (!(in >> joints)) { std::fprintf(stderr, "cannot read %s\n", path.c_str()); return 1; }
  for (int i = 0; i < joints; ++i) {
    std::string kind; int parent; double x[28];
    in >> kind >> parent;
    for (double& v : x) in >> v;
    if (!in) { std::fprintf(stderr, "bad joint line %d in %s\n", i + 1, path.c_str()); return 1; }
    Eigen::Vector3d axis(x[0], x[1], x[2]);
    Eigen::Matrix3d R; R << x[3], x[4], x[5], x[6], x[7], x[8], x[9], x[10], x[11];
    pin::SE3 placement(R, Eigen::Vector3d(x[12], x[13], x[14]));
    Eigen::Matrix3d I; I << x[19], x[20], x[21], x[22], x[23], x[24], x[25], x[26], x[27];
    pin::Inertia inertia(x[15], Eigen::Vector3d(x[16], x[17], x[18]), I);
    pin::JointIndex id;
    std::string name = "j" + std::to_string(i + 1);
    if (kind == "RX") id = model.addJoint(parent, pin::JointModelRX(), placement, name);
    else if (kind == "RY") id = model.addJoint(parent, pin::JointModelRY(), placement, name);
    else if (kind == "RZ") id = model.addJoint(parent, pin::JointModelRZ(), placement, name);
    else if (kind == "PX") id = model.addJoint(parent, pin::JointModelPX(), placement, name);
    else if (kind == "PY") id = model.addJoint(parent, pin::JointModelPY(), placement, name);
    else if (kind == "PZ") id = model.addJoint(parent, pin::JointModelPZ(), placement, name);
    else if (kind == "RU") id = model.addJoint(parent, pin::JointModelRevoluteUnaligned(axis), placement, name);
    else if (kind == "PU") id = model.addJoint(parent, pin::JointModelPrismaticUnaligned(axis), placement, name);
    else if (kind == "RUBX") id = model.addJoint(parent, pin::JointModelRUBX(), placement, name);
    else if (kind == "RUBY") id = model.addJoint(parent, pin::JointModelRUBY(), placement, name);
    else if (kind == "RUBZ") id = model.addJoint(parent, pin::JointModelRUBZ(), placement, name);
    else if (kind == "RUBU") id = model.addJoint(parent, pin::JointModelRevoluteUnboundedUnaligned(axis), placement, name);
    else if (kind == "FF") id = model.addJoint(parent, pin::JointModelFreeFlyer(), placement, name);
    else { std::fprintf(stderr, "unknown joint kind %s\n", kind.c_str()); return 1; }
    model.appendBodyToJoint(id, inertia, pin::SE3::Identity());
  }
  typedef pin::ModelTpl<C> CModel;
  typedef pin::DataTpl<C> CData;
  CModel cmodel = model.cast<C>();
  CData data(cmodel);
  const int nv = model.nv;
  std::string robot = path.substr(path.find_last_of('/') + 1);
  robot = robot.substr(0, robot.find('.'));

  Eigen::VectorXd lo = Eigen::VectorXd::Constant(model.nq, -M_PI), hi = Eigen::VectorXd::Constant(model.nq, M_PI);
  Eigen::VectorXd qd = pin::randomConfiguration(model, lo, hi);
  typedef Eigen::Matrix<C, Eigen::Dynamic, 1> VectorC;
  VectorC q = qd.cast<C>(), v(nv), tau(nv);
  for (int j = 0; j < nv; ++j) { v[j] = C(0.1 * (j + 1)); tau[j] = C(1.0 + 0.2 * j); }

  std::printf("robot,nv,algo,add,mul,div,sqrt,sincos,other,flops\n");
  auto count = [&](const char* algo, auto run) {
    reset();
    run();
    report(robot, nv, algo);
  };
  count("crba", [&] { pin::crba(cmodel, data, q); });
  count("nonLinearEffects", [&] { pin::nonLinearEffects(cmodel, data, q, v); });
  count("aba", [&] { pin::aba(cmodel, data, q, v, tau); });
  count("computeABADerivatives", [&] { pin::computeABADerivatives(cmodel, data, q, v, tau); });
  return 0;
}
