!> HDF5 layer tests (a separate fpm test, because `fsym_h5` lives in app/ beside the programs
!> and fpm lets only programs of that folder use it): round trip bit for bit with attributes
!> and slabs, an unwritable path gives an error and no file, a failed write leaves no file.
!> The last line is `N passed, N failed`; exits non-zero on failure.
program fsym_h5_tests
    use, intrinsic :: iso_fortran_env, only: int64, output_unit
    use fsym
    use fsym_h5, only: h5_file_t
    implicit none
    integer :: npass = 0, nfail = 0

    call run('h5: round trip bit for bit, attributes, slabs', t_h5_roundtrip)
    call run('h5: unwritable path gives an error and no file', t_h5_unwritable)
    call run('h5: failed write aborts, no partial file', t_h5_midway)
    write (output_unit, '(i0,a,i0,a)') npass, ' passed, ', nfail, ' failed'
    if (nfail > 0) error stop 1

contains

    !> Run one test and print its verdict.
    subroutine run(name, proc)
        character(len=*), intent(in) :: name  !! test name
        interface
            subroutine proc(err)
                implicit none
                character(len=:), allocatable, intent(out) :: err
            end subroutine proc
        end interface
        character(len=:), allocatable :: err
        call proc(err)
        if (allocated(err)) then
            nfail = nfail + 1
            write (output_unit, '(a)') 'FAIL '//name//': '//err
        else
            npass = npass + 1
            write (output_unit, '(a)') 'PASS '//name
        end if
    end subroutine run

    !> Record the first failure `msg` unless `cond` holds.
    subroutine check(err, cond, msg)
        character(len=:), allocatable, intent(inout) :: err  !! first failure
        logical, intent(in) :: cond                          !! condition that must hold
        character(len=*), intent(in) :: msg                  !! message if not
        if (cond) return
        if (.not. allocated(err)) err = msg
    end subroutine check



    !> True when a file exists.
    logical function file_there(path)
        character(len=*), intent(in) :: path
        inquire (file=path, exist=file_there)
    end function file_there

    subroutine t_h5_roundtrip(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=*), parameter :: path = 'build/test_study_roundtrip.h5'
        type(h5_file_t) :: f
        real(wp) :: r1(7), r2(3, 4), r3(2, 3, 5), slab(2, 1, 3)
        real(wp), allocatable :: b1(:), b2(:, :), b3(:, :, :), ar(:)
        integer, allocatable :: bi(:), ai(:)
        integer(ik), allocatable :: bk(:)
        character(len=:), allocatable :: s
        real(wp) :: x
        integer :: i, k, st, ival
        character(len=256) :: msg
        msg = ''
        do i = 1, size(r1)
            r1(i) = 1.0_wp / real(i, wp) - sqrt(real(i, wp)) * 1.0e-300_wp
        end do
        r2 = reshape([(sin(real(i, wp)) * 1.0e10_wp**mod(i, 5), i=1, 12)], shape(r2))
        r3 = reshape([(exp(-real(i, wp)), i=1, 30)], shape(r3))
        r1(3) = -0.0_wp
        r1(4) = huge(1.0_wp)
        r1(5) = tiny(1.0_wp) / 4.0_wp    ! subnormal
        call f%create(path, st, msg)
        call check(err, st == 0, 'create: '//trim(msg))
        if (allocated(err)) return
        call check(err, file_there(path//'.part') .and. .not. file_there(path), &
                   'while writing, only the temporary name exists')
        call f%write('a/b/c/r1', r1, st, msg); call check(err, st == 0, trim(msg))
        call f%write('r2', r2, st, msg); call check(err, st == 0, trim(msg))
        call f%write('a/r3', r3, st, msg); call check(err, st == 0, trim(msg))
        call f%write('a/i1', [1, -2, huge(1)], st, msg); call check(err, st == 0, trim(msg))
        call f%write('a/k1', [-huge(1_ik), 0_ik, 2_ik**40], st, msg)
        call check(err, st == 0, trim(msg))
        do k = 1, 4    ! slabs of 3 rows (H5MD value shape (t, n, d) seen from C)
            slab = reshape([(real(10 * k + i, wp) / 7.0_wp, i=1, 6)], shape(slab))
            call f%append('particles/x/position/value', slab, st, msg)
            call check(err, st == 0, 'append: '//trim(msg))
            call f%append('particles/x/position/step', [(int(3 * k + i, ik), i=1, 3)], st, msg)
            call check(err, st == 0, 'append: '//trim(msg))
        end do
        call f%set_attr('/', 'creator', 'fsym test', st, msg); call check(err, st == 0, trim(msg))
        call f%set_attr('/', 'creator', 'forward-symplectic test', st, msg)
        call check(err, st == 0, 'overwrite attribute: '//trim(msg))
        call f%set_attr('a', 'eps', r1(1), st, msg); call check(err, st == 0, trim(msg))
        call f%set_attr('a/r3', 'n', -7, st, msg); call check(err, st == 0, trim(msg))
        call f%set_attr('a/r3', 'c', r1, st, msg); call check(err, st == 0, trim(msg))
        call f%set_attr('a/b', 'ops', [1, 2, 3, 4], st, msg); call check(err, st == 0, trim(msg))
        call f%set_attr('a/b', 'empty', '', st, msg); call check(err, st == 0, trim(msg))
        call f%close(st, msg)
        call check(err, st == 0, 'close: '//trim(msg))
        call check(err, file_there(path) .and. .not. file_there(path//'.part'), &
                   'after close only the final name exists')
        if (allocated(err)) return

        call f%open(path, st, msg)
        call check(err, st == 0, 'open: '//trim(msg))
        if (allocated(err)) return
        call f%read('a/b/c/r1', b1, st, msg)
        call check(err, st == 0, trim(msg))
        if (st == 0) call check(err, size(b1) == size(r1) .and. &
                                all(transfer(b1, 1_int64, size(b1)) == &
                                    transfer(r1, 1_int64, size(r1))), 'r1 bits differ')
        call f%read('r2', b2, st, msg)
        if (st == 0) call check(err, all(shape(b2) == shape(r2)) .and. &
                                all(transfer(b2, 1_int64, size(b2)) == &
                                    transfer(r2, 1_int64, size(r2))), 'r2 bits differ')
        call check(err, st == 0, trim(msg))
        call f%read('a/r3', b3, st, msg)
        if (st == 0) call check(err, all(shape(b3) == shape(r3)) .and. &
                                all(transfer(b3, 1_int64, size(b3)) == &
                                    transfer(r3, 1_int64, size(r3))), 'r3 bits differ')
        call check(err, st == 0, trim(msg))
        call f%read('a/i1', bi, st, msg)
        call check(err, st == 0, trim(msg))
        if (st == 0) call check(err, all(bi == [1, -2, huge(1)]), 'integers differ')
        call f%read('a/k1', bk, st, msg)
        call check(err, st == 0, trim(msg))
        if (st == 0) call check(err, all(bk == [-huge(1_ik), 0_ik, 2_ik**40]), 'ik differ')
        call f%read('particles/x/position/value', b3, st, msg)
        call check(err, st == 0, trim(msg))
        if (st == 0) then
            call check(err, all(shape(b3) == [2, 1, 12]), 'appended shape')
            do k = 1, 4
                slab = reshape([(real(10 * k + i, wp) / 7.0_wp, i=1, 6)], shape(slab))
                call check(err, all(b3(:, :, 3 * k - 2:3 * k) == slab), 'appended slab')
            end do
        end if
        call f%read('particles/x/position/step', bk, st, msg)
        call check(err, st == 0, trim(msg))
        if (st == 0) call check(err, all(bk == [(int(i, ik), i=4, 15)]), 'appended steps')
        call f%get_attr('/', 'creator', s, st, msg)
        call check(err, st == 0 .and. s == 'forward-symplectic test', 'string attribute')
        call f%get_attr('a/b', 'empty', s, st, msg)
        call check(err, st == 0 .and. len(s) == 0, 'empty string attribute')
        call f%get_attr('a', 'eps', x, st, msg)
        call check(err, st == 0 .and. transfer(x, 1_int64) == transfer(r1(1), 1_int64), &
                   'real attribute')
        call f%get_attr('a/r3', 'n', ival, st, msg)
        call check(err, st == 0 .and. ival == -7, 'integer attribute')
        call f%get_attr('a/r3', 'c', ar, st, msg)
        call check(err, st == 0, 'real 1D attribute: '//trim(msg))
        if (st == 0) call check(err, size(ar) == size(r1) .and. &
                                all(transfer(ar, 1_int64, size(ar)) == &
                                    transfer(r1, 1_int64, size(r1))), 'real 1D attribute bits')
        call f%get_attr('a/b', 'ops', ai, st, msg)
        call check(err, st == 0, 'integer 1D attribute: '//trim(msg))
        if (st == 0) call check(err, all(ai == [1, 2, 3, 4]), 'integer 1D attribute values')
        call f%read('no/such', b1, st, msg)
        call check(err, st == FSYM_ERR_IO .and. len_trim(msg) > 0, 'missing dataset error')
        call f%close(st, msg)
        call check(err, st == 0, 'close after reading')
        open (newunit=k, file=path, status='old')
        close (k, status='delete')
    end subroutine t_h5_roundtrip

    subroutine t_h5_unwritable(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=*), parameter :: paths(2) = [character(len=40) :: &
            'build/no-such-dir-fsym/x.h5', '/proc/fsym-test-x.h5']
        type(h5_file_t) :: f
        integer :: k, st
        character(len=256) :: msg
        msg = ''
        do k = 1, size(paths)
            msg = ''
            call f%create(trim(paths(k)), st, msg)
            call check(err, st == FSYM_ERR_IO, 'no error for '//trim(paths(k)))
            call check(err, index(msg, trim(paths(k))) > 0, 'message names the path: '//trim(msg))
            call f%write('x', [1.0_wp], st, msg)
            call check(err, st /= 0, 'write to a file never opened succeeded')
            call f%close(st, msg)
            call check(err, .not. file_there(trim(paths(k))) .and. &
                       .not. file_there(trim(paths(k))//'.part'), 'file left: '//trim(paths(k)))
        end do
    end subroutine t_h5_unwritable

    subroutine t_h5_midway(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=*), parameter :: path = 'build/test_study_midway.h5'
        type(h5_file_t) :: f
        integer :: st
        character(len=256) :: msg
        msg = ''
        call f%create(path, st, msg)
        call check(err, st == 0, 'create: '//trim(msg))
        call f%write('x', [1.0_wp, 2.0_wp], st, msg)
        call check(err, st == 0, 'first write: '//trim(msg))
        call f%write('x', [3.0_wp], st, msg)     ! exists already: HDF5 refuses
        call check(err, st == FSYM_ERR_IO .and. len_trim(msg) > 0, 'duplicate dataset error')
        call f%append('y', reshape([1.0_wp, 2.0_wp], [2, 1]), st, msg)
        call f%append('y', reshape([1.0_wp, 2.0_wp, 3.0_wp], [3, 1]), st, msg)
        call check(err, st == FSYM_ERR_IO, 'slab of the wrong shape accepted')
        call f%close(st, msg)
        call check(err, st == FSYM_ERR_IO, 'close after a failed write must fail')
        call check(err, .not. file_there(path) .and. .not. file_there(path//'.part'), &
                   'partial file left behind')
    end subroutine t_h5_midway

end program fsym_h5_tests
