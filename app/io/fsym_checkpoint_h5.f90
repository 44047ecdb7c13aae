!> Checkpoint files of the programs: the library's flat checkpoint array (`fsym_checkpoint`)
!> and the program's own progress and partial results, as three 1-D double datasets of one
!> HDF5 file, written with HDF5's high-level H5LT API, and a fourth, `check`: the format tag
!> and version, the three lengths and a CRC-32 of each array. A checkpoint is written under a
!> temporary name unique to the process (`fsym_temp_name`: `path.<pid>.part`, so two jobs
!> writing the same path never share a temporary) and renamed to `path` only once complete
!> (rename is atomic on one file system); a failed write removes the temporary. A kill or a
!> full disk at any moment leaves the previous checkpoint intact.
!>
!> Reading checks, in order, and names the check that fails: the file opens as HDF5 (else
!> not HDF5 or truncated), every dataset is there (else not a checkpoint of these programs),
!> the tag and version, the lengths recorded against the datasets' (truncated or foreign),
!> and each array's CRC-32 (corrupt). The library's array is checked again, field by field,
!> by `load_checkpoint`.
module fsym_checkpoint_h5
    use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5fcreate_f, h5fopen_f, h5fclose_f, &
                    h5eset_auto_f, H5F_ACC_TRUNC_F, H5F_ACC_RDONLY_F
    use h5lt, only: h5ltmake_dataset_double_f, h5ltread_dataset_double_f, &
                    h5ltget_dataset_info_f, h5ltfind_dataset_f
    use fsym_kinds, only: wp, fsym_same
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_IO, FSYM_ERR_CHECKPOINT
    use fsym_checkpoint, only: fsym_crc32
    use fsym_h5, only: fsym_rename_file, fsym_temp_name, fsym_remove_file
    implicit none
    private

    public :: fsym_ckpt_h5_write, fsym_ckpt_h5_read

    character(len=*), parameter :: NAMES(4) = [character(len=10) :: 'integrator', 'progress', &
                                               'results', 'check']
    real(wp), parameter :: FILE_TAG = 5146736.0_wp     !! check(1)
    real(wp), parameter :: FILE_VERSION = 1.0_wp       !! check(2)
    integer, parameter :: NCHECK = 8                   !! tag, version, 3 lengths, 3 CRCs

contains

    !> Write the three arrays (and their check) to `path` atomically (temporary, rename).
    subroutine fsym_ckpt_h5_write(path, integrator, progress, results, stat, errmsg)
        character(len=*), intent(in) :: path                 !! checkpoint file
        real(wp), intent(in) :: integrator(:)                !! the library's checkpoint
        real(wp), intent(in) :: progress(:)                  !! where the program is
        real(wp), intent(in) :: results(:)                   !! results so far
        integer, intent(out) :: stat                         !! status
        character(len=*), intent(inout) :: errmsg            !! message on error
        integer(hid_t) :: f
        integer :: err, e2
        character(len=:), allocatable :: tmp
        stat = FSYM_ERR_IO
        tmp = fsym_temp_name(path)
        call h5open_f(err)
        if (err == 0) call h5eset_auto_f(0, err)
        if (err == 0) call h5fcreate_f(tmp, H5F_ACC_TRUNC_F, f, err)
        if (err /= 0) then
            call fsym_remove_file(tmp)
            errmsg = 'cannot create '//tmp//' (the last checkpoint '//path//' is kept)'; return
        end if
        call put(NAMES(1), integrator)
        call put(NAMES(2), progress)
        call put(NAMES(3), results)
        call put(NAMES(4), check_of(integrator, progress, results))
        call h5fclose_f(f, e2)
        if (err /= 0 .or. e2 /= 0) then
            call fsym_remove_file(tmp)
            errmsg = 'cannot write '//tmp//' (disk full?); removed, any earlier checkpoint '// &
                     path//' is kept'
            return
        end if
        call fsym_rename_file(tmp, path, stat, errmsg)
    contains
        subroutine put(name, x)
            character(len=*), intent(in) :: name
            real(wp), intent(in) :: x(:)
            if (err /= 0) return
            call h5ltmake_dataset_double_f(f, trim(name), 1, [size(x, kind=hsize_t)], x, err)
        end subroutine put
    end subroutine fsym_ckpt_h5_write

    !> Read the three arrays of a checkpoint file; on failure `stat` (FSYM_ERR_IO: the file
    !> cannot be opened as HDF5; FSYM_ERR_CHECKPOINT: a check failed) and a message naming
    !> the check.
    subroutine fsym_ckpt_h5_read(path, integrator, progress, results, stat, errmsg)
        character(len=*), intent(in) :: path                 !! checkpoint file
        real(wp), allocatable, intent(out) :: integrator(:)  !! the library's checkpoint
        real(wp), allocatable, intent(out) :: progress(:)    !! where the program was
        real(wp), allocatable, intent(out) :: results(:)     !! results so far
        integer, intent(out) :: stat                         !! status
        character(len=*), intent(inout) :: errmsg            !! message on error
        integer(hid_t) :: f
        integer :: err, e2, k
        real(wp), allocatable :: chk(:), want(:)
        character(len=96) :: why
        stat = FSYM_ERR_IO
        call h5open_f(err)
        if (err == 0) call h5eset_auto_f(0, err)
        if (err == 0) call h5fopen_f(path, H5F_ACC_RDONLY_F, f, err)
        if (err /= 0) then
            errmsg = 'checkpoint '//path//' refused: cannot be opened as HDF5 (missing, not '// &
                     'HDF5, or truncated)'
            return
        end if
        why = ''
        call get(NAMES(1), integrator)
        call get(NAMES(2), progress)
        call get(NAMES(3), results)
        call get(NAMES(4), chk)
        call h5fclose_f(f, e2)
        stat = FSYM_ERR_CHECKPOINT
        if (len_trim(why) == 0 .and. e2 /= 0) why = 'the file does not close cleanly'
        if (len_trim(why) == 0) then
            want = check_of(integrator, progress, results)
            if (size(chk) /= NCHECK) then
                why = 'check: dataset of the wrong length (not a checkpoint of this format)'
            else if (.not. (fsym_same(chk(1), FILE_TAG) .and. fsym_same(chk(2), FILE_VERSION))) then
                why = 'check: format tag or version differs (a foreign or newer file)'
            else if (.not. all(fsym_same(chk(3:5), want(3:5)))) then
                why = 'check: dataset lengths differ from the recorded ones (truncated)'
            else
                do k = 1, 3
                    if (.not. fsym_same(chk(5 + k), want(5 + k))) then
                        why = 'check: CRC-32 of dataset '//trim(NAMES(k))//' differs (corrupt)'
                        exit
                    end if
                end do
            end if
        end if
        if (len_trim(why) > 0) then
            errmsg = 'checkpoint '//path//' refused: '//trim(why)
            return
        end if
        stat = FSYM_SUCCESS
    contains
        subroutine get(name, x)
            character(len=*), intent(in) :: name
            real(wp), allocatable, intent(out) :: x(:)
            integer(hsize_t) :: dims(1)
            integer(size_t) :: tsize
            integer :: tclass, ast
            allocate (x(0))
            if (len_trim(why) > 0) return
            if (h5ltfind_dataset_f(f, trim(name)) /= 1) then
                why = 'no dataset '//trim(name)//' (not a checkpoint of these programs)'
                return
            end if
            dims = 0
            call h5ltget_dataset_info_f(f, trim(name), dims, tclass, tsize, err)
            if (err /= 0) then
                why = 'dataset '//trim(name)//' unreadable (corrupt)'; return
            end if
            deallocate (x)
            allocate (x(dims(1)), stat=ast)
            if (ast /= 0) then
                allocate (x(0))
                why = 'dataset '//trim(name)//' claims an impossible length (corrupt)'; return
            end if
            call h5ltread_dataset_double_f(f, trim(name), x, dims, err)
            if (err /= 0) why = 'dataset '//trim(name)//' unreadable (corrupt)'
        end subroutine get
    end subroutine fsym_ckpt_h5_read

    !> The `check` dataset of three arrays: tag, version, lengths, CRC-32 of each.
    pure function check_of(a, b, c) result(chk)
        real(wp), intent(in) :: a(:), b(:), c(:)
        real(wp) :: chk(NCHECK)
        chk = [FILE_TAG, FILE_VERSION, real(size(a), wp), real(size(b), wp), real(size(c), wp), &
               real(fsym_crc32(a), wp), real(fsym_crc32(b), wp), real(fsym_crc32(c), wp)]
    end function check_of

end module fsym_checkpoint_h5
