// Device errors in the log name their errno ("ENODEV (No such device)"): greppable and the same in
// every locale.
#pragma once

namespace dpcr::board {

// "ENAME (description)" for `error` (an errno value), in a static buffer per thread.
const char* DescribeErrno(int error);

}  // namespace dpcr::board
