!> The pFUnit driver of the suite: pFUnit's own driver (the suites come from the registry
!> file named by the macro _TEST_SUITES), plus
!>  - the option `--list`, which prints the name of every test case, one a line, and exits;
!>  - the environment variable FSYM_TEST_CASE: when set, only the case of exactly that name
!>    runs (pFUnit's `--filter` keeps every case whose name contains the pattern).
!> CMake's discovery step (fsym_test_cases.cmake) reads the list after each build and
!> registers every case with CTest, which runs it alone: each case, each method of a
!> parameterised test included, passes or fails on its own line of the CTest summary.
module fsym_test_loader
    use funit, only: TestSuite, Test
    use pf_testfilter, only: TestFilter
    implicit none
    private
    public :: load_tests, load_selected

    !> Keeps the test case of one exact name.
    type, extends(TestFilter) :: exact_name_t
        character(len=:), allocatable :: name   !! the name to keep
    contains
        procedure :: filter => exact_name_filter  !! true for that name only
    end type exact_name_t

contains

    !> True when the test's name is exactly the one wanted.
    logical function exact_name_filter(this, a_test)
        class(exact_name_t), intent(in) :: this  !! the filter
        class(Test), intent(in) :: a_test        !! a test case
        exact_name_filter = a_test%getName() == this%name
    end function exact_name_filter

    !> The suites, or only the case named by FSYM_TEST_CASE when that is set.
    function load_selected() result(suite)
        type(TestSuite) :: suite
        type(exact_name_t) :: wanted
        integer :: length, status
        suite = load_tests()
        call get_environment_variable('FSYM_TEST_CASE', length=length, status=status)
        if (status /= 0 .or. length == 0) return
        allocate (character(len=length) :: wanted%name)
        call get_environment_variable('FSYM_TEST_CASE', wanted%name)
        suite = suite%filter(wanted)
    end function load_selected

    !> Every suite of this executable, in one suite.
    function load_tests() result(suite)
#define ADDULE_TEST_SUITE(m,s) use m, only: s
#define ADD_TEST_SUITE(s) ! nothing
#include _TEST_SUITES
#undef ADDULE_TEST_SUITE
#undef ADD_TEST_SUITE
        type(TestSuite) :: suite
#define ADDULE_TEST_SUITE(m,s) ! nothing
#define ADD_TEST_SUITE(s) type(TestSuite), external :: s
#include _TEST_SUITES
#undef ADD_TEST_SUITE
#undef ADDULE_TEST_SUITE
        suite = TestSuite()
#define ADD_TEST_SUITE(s) call suite%addTest(s())
#define ADDULE_TEST_SUITE(m,s) call suite%addTest(s())
#include _TEST_SUITES
#undef ADD_TEST_SUITE
#undef ADDULE_TEST_SUITE
    end function load_tests

end module fsym_test_loader

!> `--list`: print the test-case names; otherwise pFUnit's usual command line.
program fsym_pfunit_driver
    use, intrinsic :: iso_fortran_env, only: output_unit
    use funit, only: stub, TestSuite, LoadTests_interface
    use pf_test, only: Test
    use pf_testvector, only: TestVector
    use fsym_test_loader, only: load_tests, load_selected
    implicit none
    interface
        !> pFUnit's main routine (an external procedure of libfunit).
        subroutine funit_main(load_tests, extra_initialize, extra_finalize)
            import :: LoadTests_interface
            implicit none
            procedure(LoadTests_interface) :: load_tests    !! the suites
            procedure() :: extra_initialize                 !! run before the tests
            procedure() :: extra_finalize                   !! run after the tests
        end subroutine funit_main
    end interface
    character(len=16) :: arg
    type(TestSuite) :: suite
    type(TestVector) :: cases
    class(Test), pointer :: t
    integer :: k

    arg = ''
    if (command_argument_count() == 1) call get_command_argument(1, arg)
    if (arg == '--list') then
        suite = load_tests()
        call suite%getTestCases(cases)
        do k = 1, int(cases%size())
            t => cases%at(k)
            write (output_unit, '(a)') t%getName()
        end do
    else
        call funit_main(load_selected, stub, stub)
    end if
end program fsym_pfunit_driver
