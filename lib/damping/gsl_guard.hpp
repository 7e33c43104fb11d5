#pragma once
// Internal to lib/damping: glue to GSL's C solvers.
//  - GSL's default error handler aborts the program: inside the library it is switched off for the
//    duration of a call and the status codes are turned into SolverError by the caller.
//  - A C++ exception must not unwind through GSL's C frames: the callback catches it, returns NaN,
//    and the caller rethrows it after GSL returns (rethrow_if_failed).
#include <exception>
#include <functional>
#include <limits>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>

namespace fem::damping::detail {

class GslErrorsOff {
public:
    GslErrorsOff() : previous_(gsl_set_error_handler_off()) {}
    ~GslErrorsOff() { gsl_set_error_handler(previous_); }
    GslErrorsOff(const GslErrorsOff&) = delete;
    GslErrorsOff& operator=(const GslErrorsOff&) = delete;

private:
    gsl_error_handler_t* previous_;
};

/// A std::function seen by GSL as a gsl_function; exceptions are parked, not thrown through C.
class GslCallback {
public:
    explicit GslCallback(std::function<double(double)> f) : f_(std::move(f)) {
        function_.function = &trampoline;
        function_.params = this;
    }
    GslCallback(const GslCallback&) = delete;
    GslCallback& operator=(const GslCallback&) = delete;
    gsl_function* get() { return &function_; }
    bool failed() const { return static_cast<bool>(error_); }
    void rethrow_if_failed() const {
        if (error_) std::rethrow_exception(error_);
    }

private:
    static double trampoline(double x, void* self) {
        auto* me = static_cast<GslCallback*>(self);
        if (me->error_) return std::numeric_limits<double>::quiet_NaN();
        try {
            return me->f_(x);
        } catch (...) {
            me->error_ = std::current_exception();
            return std::numeric_limits<double>::quiet_NaN();
        }
    }
    std::function<double(double)> f_;
    gsl_function function_{};
    std::exception_ptr error_;
};

}  // namespace fem::damping::detail
