!> Checkpoint files of the programs: the library's flat checkpoint array (`fsym_checkpoint`)
!> and the program's own progress and partial results, as three 1-D double datasets of one
!> HDF5 file, written with HDF5's high-level H5LT API. A checkpoint is written under a
!> temporary name (`path//'.part'`) and renamed to `path` only once complete (rename is atomic
!> on one file system), so a kill at any moment leaves the previous checkpoint intact.
module fsym_checkpoint_h5
    use hdf5, only: hid_t, hsize_t, size_t, h5open_f, h5fcreate_f, h5fopen_f, h5fclose_f, &
                    H5F_ACC_TRUNC_F, H5F_ACC_RDONLY_F
    use h5lt, only: h5ltmake_dataset_double_f, h5ltread_dataset_double_f, &
                    h5ltget_dataset_info_f
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_IO
    use fsym_h5, only: fsym_rename_file
    implicit none
    private

    public :: fsym_ckpt_h5_write, fsym_ckpt_h5_read

    character(len=*), parameter :: NAMES(3) = [character(len=10) :: 'integrator', 'progress', &
                                               'results']

contains

    !> Write the three arrays to `path` atomically (temporary file, then rename).
    subroutine fsym_ckpt_h5_write(path, integrator, progress, results, stat, errmsg)
        character(len=*), intent(in) :: path                 !! checkpoint file
        real(wp), intent(in) :: integrator(:)                !! the library's checkpoint
        real(wp), intent(in) :: progress(:)                  !! where the program is
        real(wp), intent(in) :: results(:)                   !! results so far
        integer, intent(out) :: stat                         !! status
        character(len=*), intent(inout) :: errmsg            !! message on error
        integer(hid_t) :: f
        integer :: err, e2
        stat = FSYM_ERR_IO
        call h5open_f(err)
        if (err == 0) call h5fcreate_f(path//'.part', H5F_ACC_TRUNC_F, f, err)
        if (err /= 0) then
            errmsg = 'cannot create '//path//'.part'; return
        end if
        call put(NAMES(1), integrator)
        call put(NAMES(2), progress)
        call put(NAMES(3), results)
        call h5fclose_f(f, e2)
        if (err /= 0 .or. e2 /= 0) then
            errmsg = 'cannot write '//path//'.part'; return
        end if
        call fsym_rename_file(path//'.part', path, stat, errmsg)
    contains
        subroutine put(name, x)
            character(len=*), intent(in) :: name
            real(wp), intent(in) :: x(:)
            if (err /= 0) return
            call h5ltmake_dataset_double_f(f, trim(name), 1, [size(x, kind=hsize_t)], x, err)
        end subroutine put
    end subroutine fsym_ckpt_h5_write

    !> Read the three arrays of a checkpoint file.
    subroutine fsym_ckpt_h5_read(path, integrator, progress, results, stat, errmsg)
        character(len=*), intent(in) :: path                 !! checkpoint file
        real(wp), allocatable, intent(out) :: integrator(:)  !! the library's checkpoint
        real(wp), allocatable, intent(out) :: progress(:)    !! where the program was
        real(wp), allocatable, intent(out) :: results(:)     !! results so far
        integer, intent(out) :: stat                         !! status
        character(len=*), intent(inout) :: errmsg            !! message on error
        integer(hid_t) :: f
        integer :: err, e2
        stat = FSYM_ERR_IO
        call h5open_f(err)
        if (err == 0) call h5fopen_f(path, H5F_ACC_RDONLY_F, f, err)
        if (err /= 0) then
            errmsg = 'cannot open checkpoint '//path; return
        end if
        call get(NAMES(1), integrator)
        call get(NAMES(2), progress)
        call get(NAMES(3), results)
        call h5fclose_f(f, e2)
        if (err /= 0 .or. e2 /= 0) then
            errmsg = 'cannot read checkpoint '//path; return
        end if
        stat = FSYM_SUCCESS
    contains
        subroutine get(name, x)
            character(len=*), intent(in) :: name
            real(wp), allocatable, intent(out) :: x(:)
            integer(hsize_t) :: dims(1)
            integer(size_t) :: tsize
            integer :: tclass
            allocate (x(0))
            if (err /= 0) return
            call h5ltget_dataset_info_f(f, trim(name), dims, tclass, tsize, err)
            if (err /= 0) return
            deallocate (x)
            allocate (x(dims(1)))
            call h5ltread_dataset_double_f(f, trim(name), x, dims, err)
        end subroutine get
    end subroutine fsym_ckpt_h5_read

end module fsym_checkpoint_h5
