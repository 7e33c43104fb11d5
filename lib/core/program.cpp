#include "core/program.hpp"

#include <exception>
#include <iostream>

#include "core/error.hpp"
#include "core/progress.hpp"

namespace fem {

int run_program(const char* program_name, const std::function<int()>& body) {
    try {
        return body();
    } catch (const InputError& e) {
        std::cerr << program_name << ": input error: " << e.what() << '\n';
        return 2;
    } catch (const SolverError& e) {
        std::cerr << program_name << ": solver error: " << e.what() << '\n';
        return 3;
    } catch (const Interrupted& e) {
        clear_interrupt();  // handled (a test may run the program again in-process)
        std::cerr << program_name << ": interrupted: " << e.what() << '\n';
        return 130;  // 128 + SIGINT, as a shell reports a process killed by Ctrl-C
    } catch (const std::exception& e) {
        std::cerr << program_name << ": error: " << e.what() << '\n';
        return 4;
    }
}

}  // namespace fem
