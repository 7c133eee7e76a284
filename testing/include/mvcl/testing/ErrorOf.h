#pragma once
// Catching the mvcl::Error an action throws, for tests that check what an error says.

#include <mvcl/core/Error.h>

#include <gtest/gtest.h>

#include <exception>
#include <optional>
#include <string>

namespace mvcl::test {

/// Runs `action`; returns the message of the mvcl::Error it throws, or nullopt if it returns.
/// Any other exception is let through so that the test reports it.
template <class Action> std::optional<std::string> errorFrom(Action &&action) {
    try {
        action();
    } catch (const Error &error) {
        return std::string(error.what());
    }
    return std::nullopt;
}

/// The message of the mvcl::Error `action` throws; fails the test (and returns "") when it
/// throws nothing or another exception.
template <class Action> std::string errorOf(Action &&action) {
    try {
        if (std::optional<std::string> message = errorFrom(action)) return *message;
        ADD_FAILURE() << "expected an mvcl::Error, none was thrown";
    } catch (const std::exception &e) {
        ADD_FAILURE() << "expected an mvcl::Error, got another exception: " << e.what();
    }
    return {};
}

} // namespace mvcl::test
