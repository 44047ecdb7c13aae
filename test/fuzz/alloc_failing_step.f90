!> A step never allocates, not even a failing one building its message, and neither does the
!> status report (`fsym_report`) (issue 11 item 13: a failing step allocated 13-25 times to
!> build its message). Heap allocations are counted by alloc_count.c. Exit status 1 on
!> failure.
module alloc_counter
    use, intrinsic :: iso_c_binding, only: c_long
    implicit none
    public
    integer(c_long), bind(C, name='fsym_test_mallocs') :: fsym_test_mallocs  !! the count
end module alloc_counter

program alloc_failing_step
    use, intrinsic :: iso_c_binding, only: c_long
    use alloc_counter, only: fsym_test_mallocs
    use fsym
    implicit none
    type(integrator_t) :: it
    type(kepler_model_t) :: kep
    real(wp) :: q(2, 1), v(2, 1)
    integer :: st, k, bad
    integer(c_long) :: c0, good, failing, refused, report
    character(len=256) :: msg
    bad = 0
    call it%init_by_name('C', kep, 2, 1, st)
    call kepler_paper_orbit(q(:, 1), v(:, 1))
    call it%step(kep, q, v, 0.01_wp, st, msg)
    do k = 1, 3
        c0 = fsym_test_mallocs
        call it%step(kep, q, v, 0.01_wp, st, msg)
        good = fsym_test_mallocs - c0
        c0 = fsym_test_mallocs
        call it%step(kep, q, v, 1.0e300_wp, st, msg)          ! fails mid-step
        failing = fsym_test_mallocs - c0
        c0 = fsym_test_mallocs
        call it%step(kep, q, v, 0.0_wp, st, msg)              ! refused on entry
        refused = fsym_test_mallocs - c0
        c0 = fsym_test_mallocs
        call fsym_report(FSYM_ERR_BAD_STEP, 'method C, step 2', st, msg)
        report = fsym_test_mallocs - c0
        print '(a,4(1x,i0))', 'allocations: good step, failing step, refused step, report:', &
            good, failing, refused, report
        if (good /= 0 .or. failing /= 0 .or. refused /= 0 .or. report /= 0) bad = 1
    end do
    if (bad /= 0) then
        print '(a)', 'FAIL: a step, good or failing, or its status report allocates'
        error stop 1
    end if
    print '(a)', 'PASS'
end program alloc_failing_step
