!> Runs every collected test; the last line is `N passed, N failed`; exits non-zero on failure.
!> Optional argument: a substring; only tests whose name contains it are run.
program fsym_tests
    use, intrinsic :: iso_fortran_env, only: output_unit
    use testing, only: test_t
    use test_scheme, only: collect_scheme
    use test_kepler, only: collect_kepler
    use test_integrator, only: collect_integrator
    use test_errors, only: collect_errors
    use test_stability, only: collect_stability
    use test_badinput, only: collect_badinput
    use test_nbody, only: collect_nbody
    use test_legacy, only: collect_legacy
    use test_fastpath, only: collect_fastpath
    implicit none
    type(test_t), allocatable :: tests(:)
    character(len=:), allocatable :: err
    character(len=256) :: filter
    integer :: k, npass, nfail

    filter = ''
    if (command_argument_count() > 0) call get_command_argument(1, filter)
    tests = [collect_scheme(), collect_kepler(), collect_integrator(), collect_errors(), &
             collect_nbody(), collect_legacy(), collect_fastpath(), &
             collect_stability(), collect_badinput()]
    npass = 0; nfail = 0
    do k = 1, size(tests)
        if (len_trim(filter) > 0) then
            if (index(tests(k)%name, trim(filter)) == 0) cycle
        end if
        write (output_unit, '(a)') 'RUN  '//tests(k)%name
        flush (output_unit)
        call tests(k)%proc(err)
        if (allocated(err)) then
            nfail = nfail + 1
            write (output_unit, '(a)') 'FAIL '//tests(k)%name//': '//err
        else
            npass = npass + 1
            write (output_unit, '(a)') 'PASS '//tests(k)%name
        end if
    end do
    write (output_unit, '(i0,a,i0,a)') npass, ' passed, ', nfail, ' failed'
    flush (output_unit)
    if (nfail > 0) error stop 1
end program fsym_tests
