// stairplan.optim: the optimisation core with numpy matrices. Program (built once, updated in
// place), our active-set QP solver, Ipopt and NLopt, SolveResult, and the QPS reader.
#include <memory>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "stairplan/optim/active_set_qp_solver.h"
#include "stairplan/solvers/ipopt_solver.h"
#include "stairplan/solvers/nlopt_solver.h"
#include "stairplan/optim/qps_reader.h"

namespace stairplan::python {
namespace {

using optim::Program;
using optim::VariableBlock;
using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// Python callbacks of nonlinear costs and constraints run inside a solve that released the GIL.
// The first exception one raises makes the rest return NaN (the solver then stops with an
// error status) and is raised when the solve returns.
struct CallbackError {
  std::exception_ptr error;
};

// A Python callable shared by the copies of a std::function: a copy made without the GIL (inside a
// solve) touches no Python reference count; the last owner releases it holding the GIL.
using SharedCallable = std::shared_ptr<py::function>;
SharedCallable Share(const py::function& f) {
  return SharedCallable(new py::function(f), [](py::function* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
}

template <typename F>
void Guard(const std::shared_ptr<CallbackError>& state, F body, const std::function<void()>& on_error) {
  py::gil_scoped_acquire gil;
  if (state->error) return on_error();
  try {
    body();
  } catch (py::error_already_set&) {
    state->error = std::current_exception();
    on_error();
  } catch (py::cast_error&) {
    state->error = std::current_exception();
    on_error();
  }
}

// A Program and the callback errors of its nonlinear parts.
struct PyProgram {
  Program program;
  std::shared_ptr<CallbackError> callback_error = std::make_shared<CallbackError>();
};

void AddNonlinearCost(PyProgram& p, const std::vector<VariableBlock>& blocks, const py::function& value,
                      const py::function& gradient, const std::string& name) {
  optim::NonlinearCost cost;
  cost.name = name;
  cost.blocks = blocks;
  const auto state = p.callback_error;
  cost.value = [state, value = Share(value)](const Vector& x) {
    double f = NAN;
    Guard(state, [&] { f = (*value)(x).cast<double>(); }, [&] { f = NAN; });
    return f;
  };
  cost.gradient = [state, gradient = Share(gradient)](const Vector& x, int block, Eigen::Ref<Vector> out) {
    Guard(state, [&] {
      const Vector g = (*gradient)(x, block).cast<Vector>();
      if (g.size() != out.size()) throw py::value_error("gradient: block " + std::to_string(block) + " needs " +
                                                        std::to_string(out.size()) + " entries");
      out = g;
    }, [&] { out.setConstant(NAN); });
  };
  p.program.AddNonlinearCost(std::move(cost));
}

void AddNonlinearConstraint(PyProgram& p, const std::vector<VariableBlock>& blocks, const Vector& lower,
                            const Vector& upper, const py::function& value, const py::function& jacobian,
                            const std::string& name) {
  optim::NonlinearConstraint c;
  c.name = name;
  c.blocks = blocks;
  c.lower = lower;
  c.upper = upper;
  const auto state = p.callback_error;
  c.value = [state, value = Share(value)](const Vector& x, Eigen::Ref<Vector> out) {
    Guard(state, [&] {
      const Vector v = (*value)(x).cast<Vector>();
      if (v.size() != out.size()) throw py::value_error("value: needs " + std::to_string(out.size()) + " entries");
      out = v;
    }, [&] { out.setConstant(NAN); });
  };
  c.jacobian = [state, jacobian = Share(jacobian)](const Vector& x, int block, Eigen::Ref<Matrix> out) {
    Guard(state, [&] {
      const Matrix j = (*jacobian)(x, block).cast<Matrix>();
      if (j.rows() != out.rows() || j.cols() != out.cols()) {
        throw py::value_error("jacobian: block " + std::to_string(block) + " needs shape (" +
                              std::to_string(out.rows()) + ", " + std::to_string(out.cols()) + ")");
      }
      out = j;
    }, [&] { out.setConstant(NAN); });
  };
  p.program.AddNonlinearConstraint(std::move(c));
}

optim::SolveResult Solve(optim::Solver& solver, PyProgram& p) {
  p.callback_error->error = nullptr;
  optim::SolveResult result;
  {
    py::gil_scoped_release release;
    solver.Solve(p.program, &result);
  }
  if (p.callback_error->error) std::rethrow_exception(std::exchange(p.callback_error->error, nullptr));
  return result;
}

void BindProgram(py::module_& m) {
  py::class_<VariableBlock>(m, "VariableBlock", "A contiguous block of variables: name, start, size.")
      .def_readonly("name", &VariableBlock::name)
      .def_readonly("start", &VariableBlock::start)
      .def_readonly("size", &VariableBlock::size)
      .def("__repr__", [](const VariableBlock& b) {
        return "VariableBlock('" + b.name + "', start=" + std::to_string(b.start) + ", size=" + std::to_string(b.size) + ")";
      });
  py::class_<optim::ConstraintRows>(m, "ConstraintRows", "A contiguous group of linear rows: name, start, size.")
      .def_readonly("name", &optim::ConstraintRows::name)
      .def_readonly("start", &optim::ConstraintRows::start)
      .def_readonly("size", &optim::ConstraintRows::size);
  py::class_<PyProgram>(m, "Program", R"(min 0.5 x'Hx + g'x + c + sum f_i(x)  s.t.  row_lower <= A x <= row_upper,
lower <= c_j(x) <= upper, variable_lower <= x <= variable_upper.

Built once (add_*) and updated in place (set_*) between solves, as in the C++ control loop.
Sizes and NaN are checked: ValueError naming the block or rows.)")
      .def(py::init<>())
      .def("add_variables", [](PyProgram& p, const std::string& name, int size) { return p.program.AddVariables(name, size); },
           py::arg("name"), py::arg("size"), "Adds `size` unbounded variables starting at 0.")
      .def("add_quadratic_cost", [](PyProgram& p, const VariableBlock& b, const Matrix& Q, const Vector& g) {
        p.program.AddQuadraticCost(b, Q, g);
      }, py::arg("block"), py::arg("Q"), py::arg("g"), "Adds 0.5 x_b'Q x_b + g'x_b.")
      .def("add_cross_quadratic_cost", [](PyProgram& p, const VariableBlock& a, const VariableBlock& b, const Matrix& Q) {
        p.program.AddCrossQuadraticCost(a, b, Q);
      }, py::arg("a"), py::arg("b"), py::arg("Q"), "Adds x_a'Q x_b.")
      .def("add_linear_cost", [](PyProgram& p, const VariableBlock& b, const Vector& g) { p.program.AddLinearCost(b, g); },
           py::arg("block"), py::arg("g"))
      .def("add_constant", [](PyProgram& p, double c) { p.program.AddConstant(c); }, py::arg("c"))
      .def("add_linear_constraint", [](PyProgram& p, const std::vector<std::pair<VariableBlock, Matrix>>& terms,
                                       const Vector& lower, const Vector& upper, const std::string& name) {
        return p.program.AddLinearConstraint(terms, lower, upper, name);
      }, py::arg("terms"), py::arg("lower"), py::arg("upper"), py::arg("name") = "",
           "Adds rows lower <= sum_k A_k x_{b_k} <= upper; terms is [(block, A_k)]; +-inf for one side.")
      .def("add_nonlinear_cost", &AddNonlinearCost, py::arg("blocks"), py::arg("value"), py::arg("gradient"),
           py::arg("name") = "", "Adds f(x): value(x) -> float, gradient(x, k) -> df/d blocks[k].")
      .def("add_nonlinear_constraint", &AddNonlinearConstraint, py::arg("blocks"), py::arg("lower"), py::arg("upper"),
           py::arg("value"), py::arg("jacobian"), py::arg("name") = "",
           "Adds lower <= c(x) <= upper: value(x) -> c, jacobian(x, k) -> dc/d blocks[k].")
      .def("set_variable_bounds", [](PyProgram& p, const VariableBlock& b, const Vector& lo, const Vector& hi) {
        p.program.SetVariableBounds(b, lo, hi);
      }, py::arg("block"), py::arg("lower"), py::arg("upper"))
      .def("set_linear_cost", [](PyProgram& p, const VariableBlock& b, const Vector& g) { p.program.SetLinearCost(b, g); },
           py::arg("block"), py::arg("g"))
      .def("set_constraint_bounds", [](PyProgram& p, const optim::ConstraintRows& r, const Vector& lo, const Vector& hi) {
        p.program.SetConstraintBounds(r, lo, hi);
      }, py::arg("rows"), py::arg("lower"), py::arg("upper"))
      .def("set_constraint_coefficients", [](PyProgram& p, const optim::ConstraintRows& r, const VariableBlock& b,
                                             const Matrix& a) { p.program.SetConstraintCoefficients(r, b, a); },
           py::arg("rows"), py::arg("block"), py::arg("A"))
      .def("set_initial_guess", [](PyProgram& p, const VariableBlock& b, const Vector& x0) { p.program.SetInitialGuess(b, x0); },
           py::arg("block"), py::arg("x0"))
      .def_property_readonly("num_variables", [](const PyProgram& p) { return p.program.num_variables(); })
      .def_property_readonly("num_rows", [](const PyProgram& p) { return p.program.num_rows(); })
      .def_property_readonly("blocks", [](const PyProgram& p) { return p.program.blocks(); })
      .def_property_readonly("is_quadratic", [](const PyProgram& p) { return p.program.IsQuadratic(); })
      .def_property_readonly("hessian", [](const PyProgram& p) { return p.program.hessian(); }, "H (a copy).")
      .def_property_readonly("linear_cost", [](const PyProgram& p) { return p.program.linear_cost(); })
      .def_property_readonly("constant", [](const PyProgram& p) { return p.program.constant(); })
      .def_property_readonly("constraint_matrix", [](const PyProgram& p) { return p.program.constraint_matrix(); })
      .def_property_readonly("row_lower", [](const PyProgram& p) { return p.program.row_lower(); })
      .def_property_readonly("row_upper", [](const PyProgram& p) { return p.program.row_upper(); })
      .def_property_readonly("variable_lower", [](const PyProgram& p) { return p.program.variable_lower(); })
      .def_property_readonly("variable_upper", [](const PyProgram& p) { return p.program.variable_upper(); })
      .def("objective", [](const PyProgram& p, const Vector& x) { return p.program.Objective(x); }, py::arg("x"))
      .def("max_violation", [](const PyProgram& p, const Vector& x) { return p.program.MaxViolation(x); }, py::arg("x"));
  m.def("read_qps", [](const py::object& path_arg) {
    const std::string path = PathArg(path_arg, "path");
    RequireFile(path);
    PyProgram p;
    p.program = optim::ReadQpsFile(path).program;
    return p;
  }, py::arg("path"), "Reads a QPS file (the Maros-Meszaros format) into a Program; ValueError names the line.");
}

void BindResult(py::module_& m) {
  py::enum_<optim::SolveStatus>(m, "SolveStatus", "How a solve ended (never an exception).")
      .value("SOLVED", optim::SolveStatus::kSolved)
      .value("INFEASIBLE", optim::SolveStatus::kInfeasible)
      .value("UNBOUNDED", optim::SolveStatus::kUnbounded)
      .value("ITERATION_LIMIT", optim::SolveStatus::kIterationLimit)
      .value("TIME_LIMIT", optim::SolveStatus::kTimeLimit)
      .value("NUMERICAL_ERROR", optim::SolveStatus::kNumericalError)
      .value("INVALID_INPUT", optim::SolveStatus::kInvalidInput)
      .def("__str__", [](optim::SolveStatus s) { return std::string(optim::ToString(s)); });
  py::class_<optim::SolveResult>(m, "SolveResult", "A solve's status, solution, duals and info.")
      .def_readonly("status", &optim::SolveResult::status)
      .def_property_readonly("solved", &optim::SolveResult::solved)
      .def_readonly("x", &optim::SolveResult::x)
      .def_readonly("objective", &optim::SolveResult::objective, "Including the program's constant.")
      .def_readonly("row_duals", &optim::SolveResult::row_duals)
      .def_readonly("bound_duals", &optim::SolveResult::bound_duals)
      .def_readonly("nonlinear_duals", &optim::SolveResult::nonlinear_duals)
      .def_property_readonly("iterations", [](const optim::SolveResult& r) { return r.info.iterations; })
      .def_property_readonly("solve_time_us", [](const optim::SolveResult& r) { return r.info.solve_time_us; })
      .def_property_readonly("primal_residual", [](const optim::SolveResult& r) { return r.info.primal_residual; })
      .def_property_readonly("dual_residual", [](const optim::SolveResult& r) { return r.info.dual_residual; })
      .def("__repr__", [](const optim::SolveResult& r) {
        return "<SolveResult " + std::string(optim::ToString(r.status)) + ", objective " + std::to_string(r.objective) + ">";
      });
}

template <typename SolverT, typename SettingsT>
py::class_<SolverT> BindSolver(py::module_& m, py::class_<optim::Solver>& base, const char* name, const char* doc) {
  py::class_<SolverT> cls(m, name, base, doc);
  cls.def(py::init([](const py::object& settings) {
    return settings.is_none() ? std::make_unique<SolverT>() : std::make_unique<SolverT>(settings.cast<SettingsT>());
  }), py::arg("settings") = py::none());
  cls.def_property("settings", [](SolverT& s) { return s.settings(); }, [](SolverT& s, const SettingsT& settings) {
    settings.Validate();
    s.settings() = settings;
  });
  return cls;
}

void BindSolvers(py::module_& m) {
  py::class_<optim::Solver> base(m, "Solver", "A solver back-end; solve() releases the GIL.");
  base.def("solve", &Solve, py::arg("program"), "Solves the program: a SolveResult (status, x, objective, ...).")
      .def_property_readonly("name", [](const optim::Solver& s) { return std::string(s.name()); });

  py::class_<optim::ActiveSetQpSettings>(m, "ActiveSetQpSettings")
      .def(py::init<>())
      .def_readwrite("max_iterations", &optim::ActiveSetQpSettings::max_iterations)
      .def_readwrite("max_outer_iterations", &optim::ActiveSetQpSettings::max_outer_iterations)
      .def_readwrite("time_limit_s", &optim::ActiveSetQpSettings::time_limit_s)
      .def_readwrite("feasibility_tol", &optim::ActiveSetQpSettings::feasibility_tol)
      .def_readwrite("refinement_steps", &optim::ActiveSetQpSettings::refinement_steps)
      .def_readwrite("warm_start", &optim::ActiveSetQpSettings::warm_start);
  py::class_<optim::IpoptSettings>(m, "IpoptSettings")
      .def(py::init<>())
      .def_readwrite("tolerance", &optim::IpoptSettings::tolerance)
      .def_readwrite("max_iterations", &optim::IpoptSettings::max_iterations)
      .def_readwrite("time_limit_s", &optim::IpoptSettings::time_limit_s)
      .def_readwrite("string_options", &optim::IpoptSettings::string_options)
      .def_readwrite("numeric_options", &optim::IpoptSettings::numeric_options)
      .def_readwrite("integer_options", &optim::IpoptSettings::integer_options);
  py::class_<optim::NloptSettings> nlopt_settings(m, "NloptSettings");
  py::enum_<optim::NloptSettings::Algorithm>(nlopt_settings, "Algorithm")
      .value("SLSQP", optim::NloptSettings::Algorithm::kSlsqp)
      .value("COBYLA", optim::NloptSettings::Algorithm::kCobyla);
  nlopt_settings.def(py::init<>())
      .def_readwrite("algorithm", &optim::NloptSettings::algorithm)
      .def_readwrite("xtol_rel", &optim::NloptSettings::xtol_rel)
      .def_readwrite("ftol_rel", &optim::NloptSettings::ftol_rel)
      .def_readwrite("constraint_tol", &optim::NloptSettings::constraint_tol)
      .def_readwrite("max_evaluations", &optim::NloptSettings::max_evaluations)
      .def_readwrite("time_limit_s", &optim::NloptSettings::time_limit_s);

  BindSolver<optim::ActiveSetQpSolver, optim::ActiveSetQpSettings>(m, base, "ActiveSetQpSolver",
      "Our dense dual active-set QP solver: warm-started from the previous solve's active set.");
  BindSolver<optim::IpoptSolver, optim::IpoptSettings>(m, base, "IpoptSolver", "Ipopt (interior point; QPs and NLPs).");
  BindSolver<optim::NloptSolver, optim::NloptSettings>(m, base, "NloptSolver", "NLopt (SLSQP or COBYLA; NLPs).");
}

}  // namespace

void BindOptim(py::module_& m) {
  py::module_ optim = m.def_submodule("optim", "The optimisation core: Program, solvers, SolveResult.");
  BindProgram(optim);
  BindResult(optim);
  BindSolvers(optim);
}

}  // namespace stairplan::python
