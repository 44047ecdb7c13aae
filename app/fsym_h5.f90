!> A small HDF5 layer for the programs in `app/` (the core does no I/O). Every HDF5 call's
!> status is checked and turned into `stat`/`errmsg` (`FSYM_ERR_IO`).
!>
!> A file is created under a temporary name (`path//'.part'`) and renamed to `path` only by a
!> successful `close`; `abort` (or any failed write, or a close that fails) deletes the
!> temporary, so an unwritable path or a failure mid-way leaves no partial file.
!>
!> Objects are named by their path inside the file (`'particles/FR/position/value'`); writes
!> create missing parent groups. Datasets: `real(wp)` rank 1-3, default integer and
!> `integer(ik)` rank 1, written whole (`write`) or appended in slabs along the last Fortran
!> dimension (`append`, chunked and extendible; the last Fortran dimension is the first,
!> slowest, dimension seen from C/h5py). Attributes on the file (`'/'`), groups and datasets:
!> string, real scalar, integer scalar, real 1D, integer 1D. Readers for all of them.
module fsym_h5
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char, c_ptr, c_loc
    use hdf5
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_IO, fsym_report, fsym_pass
    implicit none
    private

    public :: h5_file_t, fsym_rename_file

    integer, parameter :: MODE_CLOSED = 0, MODE_WRITE = 1, MODE_READ = 2

    !> An HDF5 file opened for writing (atomic, through a temporary name) or for reading.
    type :: h5_file_t
        integer(hid_t) :: id = -1                !! HDF5 file identifier
        integer :: mode = MODE_CLOSED            !! closed, write or read
        logical :: failed = .false.              !! a write failed: close will abort
        character(len=:), allocatable :: path    !! final file name
        character(len=:), allocatable :: tmp     !! temporary name while writing
    contains
        procedure :: create => h5_create
        procedure :: open => h5_open_read
        procedure :: close => h5_close
        procedure :: abort => h5_abort
        procedure :: make_group => h5_make_group
        procedure :: exists => h5_exists
        procedure, private :: w_r1, w_r2, w_r3, w_i1, w_ik1
        generic :: write => w_r1, w_r2, w_r3, w_i1, w_ik1
        procedure, private :: a_r1, a_r2, a_r3, a_i1, a_ik1
        generic :: append => a_r1, a_r2, a_r3, a_i1, a_ik1
        procedure, private :: r_r1, r_r2, r_r3, r_i1, r_ik1
        generic :: read => r_r1, r_r2, r_r3, r_i1, r_ik1
        procedure, private :: sa_s, sa_r0, sa_i0, sa_r1, sa_i1
        generic :: set_attr => sa_s, sa_r0, sa_i0, sa_r1, sa_i1
        procedure, private :: ga_s, ga_r0, ga_i0, ga_r1, ga_i1
        generic :: get_attr => ga_s, ga_r0, ga_i0, ga_r1, ga_i1
        final :: h5_final
    end type h5_file_t

    interface
        !> C library `rename`.
        function c_rename(old, new) bind(C, name='rename') result(r)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: old(*)  !! old name, NUL-terminated
            character(kind=c_char), intent(in) :: new(*)  !! new name, NUL-terminated
            integer(c_int) :: r
        end function c_rename
        !> C library `remove`.
        function c_remove(name) bind(C, name='remove') result(r)
            import :: c_char, c_int
            implicit none
            character(kind=c_char), intent(in) :: name(*)  !! file name, NUL-terminated
            integer(c_int) :: r
        end function c_remove
    end interface

    logical :: lib_open = .false.

contains

    ! ---------------------------------------------------------------- helpers

    !> True (and the error reported) when an HDF5 status is negative.
    logical function bad(ierr, what, stat, errmsg)
        integer, intent(in) :: ierr                           !! HDF5 status
        character(len=*), intent(in) :: what                  !! the call, in context
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        bad = ierr < 0
        if (bad) then
            call fsym_report(FSYM_ERR_IO, 'HDF5 '//what, stat, errmsg)
        else if (present(stat)) then
            stat = FSYM_SUCCESS
        end if
    end function bad

    !> Initialise the HDF5 library once and silence its own error printing.
    subroutine lib_init(ierr)
        integer, intent(out) :: ierr  !! HDF5 status
        ierr = 0
        if (lib_open) return
        call h5open_f(ierr)
        if (ierr < 0) return
        call h5eset_auto_f(0, ierr)
        lib_open = ierr >= 0
    end subroutine lib_init

    !> Close any HDF5 identifier (dataset, group, space, type, property list, attribute),
    !> ignoring errors; used on every exit path.
    subroutine release(id)
        integer(hid_t), intent(inout) :: id  !! identifier; set to -1
        integer :: t, ierr
        if (id < 0) return
        call h5iget_type_f(id, t, ierr)
        if (ierr >= 0) then
            if (t == H5I_DATASET_F) then
                call h5dclose_f(id, ierr)
            else if (t == H5I_GROUP_F) then
                call h5gclose_f(id, ierr)
            else if (t == H5I_DATASPACE_F) then
                call h5sclose_f(id, ierr)
            else if (t == H5I_DATATYPE_F) then
                call h5tclose_f(id, ierr)
            else if (t == H5I_ATTR_F) then
                call h5aclose_f(id, ierr)
            else if (t == H5I_GENPROP_LST_F) then
                call h5pclose_f(id, ierr)
            end if
        end if
        id = -1
    end subroutine release

    !> Fail unless the file is open in the needed mode.
    logical function not_open(self, mode, what, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        integer, intent(in) :: mode                           !! needed mode
        character(len=*), intent(in) :: what                  !! operation
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        not_open = self%mode /= mode
        if (not_open) then
            call fsym_report(FSYM_ERR_IO, what//': file not open for this', stat, errmsg)
            if (self%mode == MODE_WRITE) self%failed = .true.
        end if
    end function not_open

    !> Record a failed write (the file will be aborted on close).
    subroutine note_fail(self, stat)
        class(h5_file_t), intent(inout) :: self  !! the file
        integer, intent(in), optional :: stat    !! status of the write
        if (present(stat)) then
            if (stat /= FSYM_SUCCESS) self%failed = .true.
        end if
    end subroutine note_fail

    !> Text of a path normalised to start with '/'.
    pure function abspath(path) result(p)
        character(len=*), intent(in) :: path  !! path inside the file
        character(len=:), allocatable :: p
        p = trim(path)
        if (len(p) == 0) then
            p = '/'
        else if (p(1:1) /= '/') then
            p = '/'//p
        end if
    end function abspath

    !> HDF5 type of real(wp).
    integer(hid_t) function t_real()
        t_real = h5kind_to_type(wp, H5_REAL_KIND)
    end function t_real

    !> HDF5 type of integer(ik).
    integer(hid_t) function t_ik()
        t_ik = h5kind_to_type(ik, H5_INTEGER_KIND)
    end function t_ik

    ! ---------------------------------------------------------------- files

    !> Rename a file with the C library's `rename` (atomic on one file system); used to put
    !> any finished output (e.g. a text report written under a temporary name) in place.
    subroutine fsym_rename_file(from, to, stat, errmsg)
        character(len=*), intent(in) :: from                  !! current name
        character(len=*), intent(in) :: to                    !! new name
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        if (c_rename(trim(from)//c_null_char, trim(to)//c_null_char) /= 0) then
            call fsym_report(FSYM_ERR_IO, 'cannot rename '//trim(from)//' to '//trim(to), &
                             stat, errmsg)
        else if (present(stat)) then
            stat = FSYM_SUCCESS
        end if
    end subroutine fsym_rename_file

    !> Create `path` for writing (under the temporary name `path//'.part'`).
    subroutine h5_create(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! final file name
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer :: ierr
        if (self%mode /= MODE_CLOSED) call self%abort()
        call lib_init(ierr)
        if (bad(ierr, 'library initialisation', stat, errmsg)) return
        self%path = trim(path)
        self%tmp = trim(path)//'.part'
        self%failed = .false.
        call h5fcreate_f(self%tmp, H5F_ACC_TRUNC_F, self%id, ierr)
        if (bad(ierr, 'cannot create '//self%tmp, stat, errmsg)) then
            self%id = -1
            ierr = c_remove(self%tmp//c_null_char)
            return
        end if
        self%mode = MODE_WRITE
    end subroutine h5_create

    !> Open an existing file read-only.
    subroutine h5_open_read(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! file name
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer :: ierr
        if (self%mode /= MODE_CLOSED) call self%abort()
        call lib_init(ierr)
        if (bad(ierr, 'library initialisation', stat, errmsg)) return
        self%path = trim(path)
        call h5fopen_f(self%path, H5F_ACC_RDONLY_F, self%id, ierr)
        if (bad(ierr, 'cannot open '//self%path, stat, errmsg)) then
            self%id = -1
            return
        end if
        self%mode = MODE_READ
    end subroutine h5_open_read

    !> Close the file. A written file gets its final name only here, and only when every
    !> write succeeded; otherwise the temporary is deleted and an error returned.
    subroutine h5_close(self, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer :: ierr, mode
        mode = self%mode
        if (present(stat)) stat = FSYM_SUCCESS
        if (mode == MODE_CLOSED) return
        if (mode == MODE_WRITE .and. self%failed) then
            call self%abort()
            call fsym_report(FSYM_ERR_IO, 'a write failed; '//self%path//' not written', &
                             stat, errmsg)
            return
        end if
        call h5fclose_f(self%id, ierr)
        self%id = -1
        self%mode = MODE_CLOSED
        if (bad(ierr, 'cannot close '//self%path, stat, errmsg)) then
            if (mode == MODE_WRITE) ierr = c_remove(self%tmp//c_null_char)
            return
        end if
        if (mode == MODE_WRITE) then
            if (c_rename(self%tmp//c_null_char, self%path//c_null_char) /= 0) then
                ierr = c_remove(self%tmp//c_null_char)
                call fsym_report(FSYM_ERR_IO, 'cannot rename '//self%tmp//' to '// &
                                 self%path, stat, errmsg)
            end if
        end if
    end subroutine h5_close

    !> Close without keeping anything: a file being written is deleted.
    subroutine h5_abort(self)
        class(h5_file_t), intent(inout) :: self  !! the file
        integer :: ierr
        if (self%mode == MODE_CLOSED) return
        call h5fclose_f(self%id, ierr)
        if (self%mode == MODE_WRITE) ierr = c_remove(self%tmp//c_null_char)
        self%id = -1
        self%mode = MODE_CLOSED
    end subroutine h5_abort

    !> A file still open when it goes out of scope is aborted.
    subroutine h5_final(self)
        type(h5_file_t), intent(inout) :: self  !! the file
        call h5_abort(self)
    end subroutine h5_final

    !> True when an object exists at `path`.
    logical function h5_exists(self, path)
        class(h5_file_t), intent(inout) :: self  !! the file
        character(len=*), intent(in) :: path     !! path inside the file
        character(len=:), allocatable :: p
        integer :: i, ierr
        logical :: ok
        h5_exists = .false.
        if (self%mode == MODE_CLOSED) return
        p = abspath(path)
        if (p == '/') then
            h5_exists = .true.; return
        end if
        do i = 2, len(p)    ! every prefix must exist before h5lexists_f may be asked
            if (i < len(p) .and. p(i:i) /= '/') cycle
            if (i < len(p)) then
                call h5lexists_f(self%id, p(1:i - 1), ok, ierr)
            else
                call h5lexists_f(self%id, p, ok, ierr)
            end if
            if (ierr < 0 .or. .not. ok) return
        end do
        h5_exists = .true.
    end function h5_exists

    !> Create the group `path` and any missing parents.
    subroutine h5_make_group(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! group path
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        character(len=:), allocatable :: p
        integer(hid_t) :: gid
        integer :: i, ierr
        if (not_open(self, MODE_WRITE, 'make_group '//trim(path), stat, errmsg)) return
        if (present(stat)) stat = FSYM_SUCCESS
        p = abspath(path)
        p = p//'/'    ! every prefix ending before a '/' is a group
        do i = 2, len(p) - 1
            if (p(i + 1:i + 1) /= '/' .or. p(i:i) == '/') cycle
            if (self%exists(p(1:i))) cycle
            call h5gcreate_f(self%id, p(1:i), gid, ierr)
            if (bad(ierr, 'cannot create group '//p(1:i), stat, errmsg)) then
                self%failed = .true.; return
            end if
            call h5gclose_f(gid, ierr)
            if (bad(ierr, 'close group '//p(1:i), stat, errmsg)) then
                self%failed = .true.; return
            end if
        end do
    end subroutine h5_make_group

    !> Create the parent group of the object at `path`.
    subroutine make_parent(self, path, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! object path
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        character(len=:), allocatable :: p
        integer :: i
        if (present(stat)) stat = FSYM_SUCCESS
        p = abspath(path)
        i = index(p, '/', back=.true.)
        if (i > 1) call self%make_group(p(1:i - 1), stat, errmsg)
    end subroutine make_parent

    ! ---------------------------------------------------------------- datasets (raw)

    !> Write a whole dataset of shape `dims` from the buffer at `ptr`.
    subroutine write_raw(self, path, tid, dims, ptr, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        integer(hid_t), intent(in) :: tid                     !! HDF5 memory and file type
        integer(hsize_t), intent(in) :: dims(:)               !! shape (Fortran order)
        type(c_ptr), intent(in) :: ptr                        !! data
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(hid_t) :: sid, did
        integer :: ierr, st
        character(len=512) :: msg
        character(len=:), allocatable :: p
        msg = ''
        sid = -1; did = -1; st = FSYM_SUCCESS
        if (not_open(self, MODE_WRITE, 'write '//trim(path), stat, errmsg)) return
        p = abspath(path)
        call make_parent(self, p, st, msg)
        ok: block
            if (st /= FSYM_SUCCESS) exit ok
            call h5screate_simple_f(size(dims), dims, sid, ierr)
            if (bad(ierr, 'dataspace for '//p, st, msg)) exit ok
            call h5dcreate_f(self%id, p, tid, sid, did, ierr)
            if (bad(ierr, 'cannot create dataset '//p, st, msg)) exit ok
            call h5dwrite_f(did, tid, ptr, ierr)
            if (bad(ierr, 'cannot write dataset '//p, st, msg)) exit ok
        end block ok
        call release(did); call release(sid)
        call note_fail(self, st)
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine write_raw

    !> Append a slab of shape `dims` along the last dimension of an extendible dataset
    !> (created, chunked, on the first append).
    subroutine append_raw(self, path, tid, dims, ptr, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        integer(hid_t), intent(in) :: tid                     !! HDF5 memory and file type
        integer(hsize_t), intent(in) :: dims(:)               !! slab shape (Fortran order)
        type(c_ptr), intent(in) :: ptr                        !! data
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(hid_t) :: sid, did, pid, msid
        integer(hsize_t) :: cur(size(dims)), mx(size(dims)), chunk(size(dims)), off(size(dims))
        integer :: ierr, st, r, rk
        character(len=512) :: msg
        character(len=:), allocatable :: p
        msg = ''
        sid = -1; did = -1; pid = -1; msid = -1; st = FSYM_SUCCESS
        if (not_open(self, MODE_WRITE, 'append '//trim(path), stat, errmsg)) return
        p = abspath(path)
        r = size(dims)
        ok: block
            if (.not. self%exists(p)) then
                call make_parent(self, p, st, msg)
                if (st /= FSYM_SUCCESS) exit ok
                cur = dims; cur(r) = 0
                mx = dims; mx(r) = H5S_UNLIMITED_F
                chunk = dims
                chunk(r) = max(1_hsize_t, min(4096_hsize_t, 32768_hsize_t / &
                               max(1_hsize_t, product(dims(1:r - 1)))))
                call h5screate_simple_f(r, cur, sid, ierr, mx)
                if (bad(ierr, 'dataspace for '//p, st, msg)) exit ok
                call h5pcreate_f(H5P_DATASET_CREATE_F, pid, ierr)
                if (bad(ierr, 'property list for '//p, st, msg)) exit ok
                call h5pset_chunk_f(pid, r, chunk, ierr)
                if (bad(ierr, 'chunking of '//p, st, msg)) exit ok
                call h5dcreate_f(self%id, p, tid, sid, did, ierr, pid)
                if (bad(ierr, 'cannot create dataset '//p, st, msg)) exit ok
                call release(sid)
            else
                call h5dopen_f(self%id, p, did, ierr)
                if (bad(ierr, 'cannot open dataset '//p, st, msg)) exit ok
                call h5dget_space_f(did, sid, ierr)
                if (bad(ierr, 'dataspace of '//p, st, msg)) exit ok
                call h5sget_simple_extent_ndims_f(sid, rk, ierr)
                if (bad(min(ierr, merge(-1, 0, rk /= r)), 'rank of '//p, st, msg)) exit ok
                call h5sget_simple_extent_dims_f(sid, cur, mx, ierr)
                if (bad(ierr, 'shape of '//p, st, msg)) exit ok
                call release(sid)
                if (any(cur(1:r - 1) /= dims(1:r - 1))) then
                    call fsym_report(FSYM_ERR_IO, 'slab shape does not match '//p, st, msg)
                    exit ok
                end if
            end if
            off = 0; off(r) = cur(r)
            cur(r) = cur(r) + dims(r)
            call h5dset_extent_f(did, cur, ierr)
            if (bad(ierr, 'cannot extend '//p, st, msg)) exit ok
            call h5dget_space_f(did, sid, ierr)
            if (bad(ierr, 'dataspace of '//p, st, msg)) exit ok
            call h5sselect_hyperslab_f(sid, H5S_SELECT_SET_F, off, dims, ierr)
            if (bad(ierr, 'slab selection in '//p, st, msg)) exit ok
            call h5screate_simple_f(r, dims, msid, ierr)
            if (bad(ierr, 'memory space for '//p, st, msg)) exit ok
            call h5dwrite_f(did, tid, ptr, ierr, msid, sid)
            if (bad(ierr, 'cannot append to '//p, st, msg)) exit ok
        end block ok
        call release(msid); call release(sid); call release(pid); call release(did)
        call note_fail(self, st)
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine append_raw

    !> Open a dataset and give its shape (Fortran order); `did` stays open on success.
    subroutine open_dataset(self, path, rank, did, dims, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        integer, intent(in) :: rank                           !! expected rank
        integer(hid_t), intent(out) :: did                    !! dataset identifier
        integer(hsize_t), intent(out) :: dims(rank)           !! shape
        integer, intent(out) :: stat                          !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(hid_t) :: sid
        integer(hsize_t) :: mx(rank)
        integer :: ierr, r
        did = -1; sid = -1; dims = 0; stat = FSYM_SUCCESS
        if (not_open(self, MODE_READ, 'read '//trim(path), stat, errmsg)) return
        ok: block
            call h5dopen_f(self%id, abspath(path), did, ierr)
            if (bad(ierr, 'cannot open dataset '//abspath(path), stat, errmsg)) exit ok
            call h5dget_space_f(did, sid, ierr)
            if (bad(ierr, 'dataspace of '//abspath(path), stat, errmsg)) exit ok
            call h5sget_simple_extent_ndims_f(sid, r, ierr)
            if (bad(min(ierr, merge(-1, 0, r /= rank)), 'rank of '//abspath(path), &
                    stat, errmsg)) exit ok
            call h5sget_simple_extent_dims_f(sid, dims, mx, ierr)
            if (bad(ierr, 'shape of '//abspath(path), stat, errmsg)) exit ok
        end block ok
        call release(sid)
        if (stat /= FSYM_SUCCESS) call release(did)
    end subroutine open_dataset

    !> Read an open dataset into the buffer at `ptr` and close it.
    subroutine read_close(did, tid, ptr, path, stat, errmsg)
        integer(hid_t), intent(inout) :: did                  !! dataset identifier
        integer(hid_t), intent(in) :: tid                     !! HDF5 memory type
        type(c_ptr), intent(in) :: ptr                        !! buffer
        character(len=*), intent(in) :: path                  !! dataset path (messages)
        integer, intent(out) :: stat                          !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        type(c_ptr) :: buf
        integer :: ierr
        buf = ptr    ! h5dread_f wants a variable
        call h5dread_f(did, tid, buf, ierr)
        if (.not. bad(ierr, 'cannot read '//path, stat, errmsg)) stat = FSYM_SUCCESS
        call release(did)
    end subroutine read_close

    ! ---------------------------------------------------------------- datasets (typed)

    !> Write a real 1D dataset.
    subroutine w_r1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        real(wp), intent(in), target, contiguous :: x(:)      !! data
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        call write_raw(self, path, t_real(), int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine w_r1

    !> Write a real 2D dataset.
    subroutine w_r2(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :)   !! data
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        call write_raw(self, path, t_real(), int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine w_r2

    !> Write a real 3D dataset.
    subroutine w_r3(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                  !! the file
        character(len=*), intent(in) :: path                     !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :, :)   !! data
        integer, intent(out), optional :: stat                   !! status code
        character(len=*), intent(inout), optional :: errmsg      !! message on error
        call write_raw(self, path, t_real(), int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine w_r3

    !> Write a default-integer 1D dataset.
    subroutine w_i1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        integer, intent(in), target, contiguous :: x(:)       !! data
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        call write_raw(self, path, H5T_NATIVE_INTEGER, int(shape(x), hsize_t), c_loc(x), &
                       stat, errmsg)
    end subroutine w_i1

    !> Write an integer(ik) 1D dataset.
    subroutine w_ik1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        integer(ik), intent(in), target, contiguous :: x(:)   !! data
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        call write_raw(self, path, t_ik(), int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine w_ik1

    !> Append real values to an extendible 1D dataset.
    subroutine a_r1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        real(wp), intent(in), target, contiguous :: x(:)      !! slab
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        call append_raw(self, path, t_real(), int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine a_r1

    !> Append columns x(:, k) (rows seen from C/h5py) to an extendible real 2D dataset.
    subroutine a_r2(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :)   !! slab
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        call append_raw(self, path, t_real(), int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine a_r2

    !> Append x(:, :, k) to an extendible real 3D dataset (H5MD `value` of shape (d, n, t)).
    subroutine a_r3(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                  !! the file
        character(len=*), intent(in) :: path                     !! dataset path
        real(wp), intent(in), target, contiguous :: x(:, :, :)   !! slab
        integer, intent(out), optional :: stat                   !! status code
        character(len=*), intent(inout), optional :: errmsg      !! message on error
        call append_raw(self, path, t_real(), int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine a_r3

    !> Append default integers to an extendible 1D dataset.
    subroutine a_i1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        integer, intent(in), target, contiguous :: x(:)       !! slab
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        call append_raw(self, path, H5T_NATIVE_INTEGER, int(shape(x), hsize_t), c_loc(x), &
                        stat, errmsg)
    end subroutine a_i1

    !> Append integer(ik) values to an extendible 1D dataset.
    subroutine a_ik1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! dataset path
        integer(ik), intent(in), target, contiguous :: x(:)   !! slab
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        call append_raw(self, path, t_ik(), int(shape(x), hsize_t), c_loc(x), stat, errmsg)
    end subroutine a_ik1

    !> Read a real 1D dataset.
    subroutine r_r1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                        !! the file
        character(len=*), intent(in) :: path                           !! dataset path
        real(wp), allocatable, target, intent(out) :: x(:)             !! data
        integer, intent(out), optional :: stat                         !! status code
        character(len=*), intent(inout), optional :: errmsg            !! message on error
        integer(hid_t) :: did
        integer(hsize_t) :: n(1)
        integer :: st
        character(len=512) :: msg
        msg = ''
        call open_dataset(self, path, 1, did, n, st, msg)
        if (st == FSYM_SUCCESS) then
            allocate (x(n(1)))
            if (size(x) > 0) call read_close(did, t_real(), c_loc(x), path, st, msg)
            call release(did)
        end if
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine r_r1

    !> Read a real 2D dataset.
    subroutine r_r2(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                        !! the file
        character(len=*), intent(in) :: path                           !! dataset path
        real(wp), allocatable, target, intent(out) :: x(:, :)          !! data
        integer, intent(out), optional :: stat                         !! status code
        character(len=*), intent(inout), optional :: errmsg            !! message on error
        integer(hid_t) :: did
        integer(hsize_t) :: n(2)
        integer :: st
        character(len=512) :: msg
        msg = ''
        call open_dataset(self, path, 2, did, n, st, msg)
        if (st == FSYM_SUCCESS) then
            allocate (x(n(1), n(2)))
            if (size(x) > 0) call read_close(did, t_real(), c_loc(x), path, st, msg)
            call release(did)
        end if
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine r_r2

    !> Read a real 3D dataset.
    subroutine r_r3(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                        !! the file
        character(len=*), intent(in) :: path                           !! dataset path
        real(wp), allocatable, target, intent(out) :: x(:, :, :)       !! data
        integer, intent(out), optional :: stat                         !! status code
        character(len=*), intent(inout), optional :: errmsg            !! message on error
        integer(hid_t) :: did
        integer(hsize_t) :: n(3)
        integer :: st
        character(len=512) :: msg
        msg = ''
        call open_dataset(self, path, 3, did, n, st, msg)
        if (st == FSYM_SUCCESS) then
            allocate (x(n(1), n(2), n(3)))
            if (size(x) > 0) call read_close(did, t_real(), c_loc(x), path, st, msg)
            call release(did)
        end if
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine r_r3

    !> Read a default-integer 1D dataset.
    subroutine r_i1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                        !! the file
        character(len=*), intent(in) :: path                           !! dataset path
        integer, allocatable, target, intent(out) :: x(:)              !! data
        integer, intent(out), optional :: stat                         !! status code
        character(len=*), intent(inout), optional :: errmsg            !! message on error
        integer(hid_t) :: did
        integer(hsize_t) :: n(1)
        integer :: st
        character(len=512) :: msg
        msg = ''
        call open_dataset(self, path, 1, did, n, st, msg)
        if (st == FSYM_SUCCESS) then
            allocate (x(n(1)))
            if (size(x) > 0) call read_close(did, H5T_NATIVE_INTEGER, c_loc(x), path, st, &
                                             msg)
            call release(did)
        end if
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine r_i1

    !> Read an integer(ik) 1D dataset.
    subroutine r_ik1(self, path, x, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                        !! the file
        character(len=*), intent(in) :: path                           !! dataset path
        integer(ik), allocatable, target, intent(out) :: x(:)          !! data
        integer, intent(out), optional :: stat                         !! status code
        character(len=*), intent(inout), optional :: errmsg            !! message on error
        integer(hid_t) :: did
        integer(hsize_t) :: n(1)
        integer :: st
        character(len=512) :: msg
        msg = ''
        call open_dataset(self, path, 1, did, n, st, msg)
        if (st == FSYM_SUCCESS) then
            allocate (x(n(1)))
            if (size(x) > 0) call read_close(did, t_ik(), c_loc(x), path, st, msg)
            call release(did)
        end if
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine r_ik1

    ! ---------------------------------------------------------------- attributes (raw)

    !> Write attribute `name` (replacing it) of shape `dims` (scalar if empty) on the object
    !> at `path` from the buffer at `ptr`.
    subroutine set_attr_raw(self, path, name, tid, dims, ptr, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! object path ('/' = file)
        character(len=*), intent(in) :: name                  !! attribute name
        integer(hid_t), intent(in) :: tid                     !! HDF5 type
        integer(hsize_t), intent(in) :: dims(:)               !! shape; size 0 = scalar
        type(c_ptr), intent(in) :: ptr                        !! data
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(hid_t) :: oid, sid, aid
        integer :: ierr, st
        character(len=512) :: msg
        logical :: there
        character(len=:), allocatable :: what
        msg = ''
        oid = -1; sid = -1; aid = -1; st = FSYM_SUCCESS
        if (not_open(self, MODE_WRITE, 'attribute '//trim(name), stat, errmsg)) return
        what = 'attribute '//trim(name)//' of '//abspath(path)
        ok: block
            call h5oopen_f(self%id, abspath(path), oid, ierr)
            if (bad(ierr, 'cannot open object for '//what, st, msg)) exit ok
            call h5aexists_f(oid, trim(name), there, ierr)
            if (bad(ierr, 'exists '//what, st, msg)) exit ok
            if (there) then
                call h5adelete_f(oid, trim(name), ierr)
                if (bad(ierr, 'delete '//what, st, msg)) exit ok
            end if
            if (size(dims) == 0) then
                call h5screate_f(H5S_SCALAR_F, sid, ierr)
            else
                call h5screate_simple_f(size(dims), dims, sid, ierr)
            end if
            if (bad(ierr, 'dataspace of '//what, st, msg)) exit ok
            call h5acreate_f(oid, trim(name), tid, sid, aid, ierr)
            if (bad(ierr, 'cannot create '//what, st, msg)) exit ok
            call h5awrite_f(aid, tid, ptr, ierr)
            if (bad(ierr, 'cannot write '//what, st, msg)) exit ok
        end block ok
        call release(aid); call release(sid)
        if (oid >= 0) call h5oclose_f(oid, ierr)
        call note_fail(self, st)
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine set_attr_raw

    !> Open attribute `name` of the object at `path`; give its element count and keep
    !> `oid`, `aid` open on success.
    subroutine open_attr(self, path, name, oid, aid, n, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! object path
        character(len=*), intent(in) :: name                  !! attribute name
        integer(hid_t), intent(out) :: oid, aid               !! object and attribute ids
        integer(hsize_t), intent(out) :: n                    !! number of elements
        integer, intent(out) :: stat                          !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(hid_t) :: sid
        integer(hssize_t) :: npts
        integer :: ierr
        character(len=:), allocatable :: what
        oid = -1; aid = -1; sid = -1; n = 0; stat = FSYM_SUCCESS
        if (not_open(self, MODE_READ, 'attribute '//trim(name), stat, errmsg)) return
        what = 'attribute '//trim(name)//' of '//abspath(path)
        ok: block
            call h5oopen_f(self%id, abspath(path), oid, ierr)
            if (bad(ierr, 'cannot open object for '//what, stat, errmsg)) exit ok
            call h5aopen_f(oid, trim(name), aid, ierr)
            if (bad(ierr, 'cannot open '//what, stat, errmsg)) exit ok
            call h5aget_space_f(aid, sid, ierr)
            if (bad(ierr, 'dataspace of '//what, stat, errmsg)) exit ok
            call h5sget_simple_extent_npoints_f(sid, npts, ierr)
            if (bad(ierr, 'size of '//what, stat, errmsg)) exit ok
            n = int(npts, hsize_t)
        end block ok
        call release(sid)
        if (stat /= FSYM_SUCCESS) call close_attr(oid, aid)
    end subroutine open_attr

    !> Read an open attribute into `ptr` (unless `stat` already failed) and close it.
    subroutine read_attr_close(oid, aid, tid, ptr, name, stat, errmsg)
        integer(hid_t), intent(inout) :: oid, aid             !! object and attribute ids
        integer(hid_t), intent(in) :: tid                     !! memory type
        type(c_ptr), intent(in) :: ptr                        !! buffer
        character(len=*), intent(in) :: name                  !! attribute name (messages)
        integer, intent(inout) :: stat                        !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        type(c_ptr) :: buf
        integer :: ierr
        if (stat == FSYM_SUCCESS) then
            buf = ptr    ! h5aread_f wants a variable
            call h5aread_f(aid, tid, buf, ierr)
            if (ierr < 0) call fsym_report(FSYM_ERR_IO, 'HDF5 cannot read attribute '// &
                                           trim(name), stat, errmsg)
        end if
        call close_attr(oid, aid)
    end subroutine read_attr_close

    !> Close an attribute and its object.
    subroutine close_attr(oid, aid)
        integer(hid_t), intent(inout) :: oid, aid  !! object and attribute ids
        integer :: ierr
        call release(aid)
        if (oid >= 0) call h5oclose_f(oid, ierr)
        oid = -1
    end subroutine close_attr

    ! ---------------------------------------------------------------- attributes (typed)

    !> Set a string attribute (fixed length, NUL-padded).
    subroutine sa_s(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! object path ('/' = file)
        character(len=*), intent(in) :: name                  !! attribute name
        character(len=*), intent(in) :: value                 !! value
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        character(kind=c_char), allocatable, target :: buf(:)
        integer(hid_t) :: tid
        integer :: ierr, i
        integer(hsize_t) :: none(0)
        allocate (buf(max(1, len(value))))
        buf = c_null_char
        do i = 1, len(value)
            buf(i) = value(i:i)
        end do
        tid = -1
        call h5tcopy_f(H5T_C_S1, tid, ierr)
        if (bad(ierr, 'string type', stat, errmsg)) then
            self%failed = .true.; return
        end if
        call h5tset_size_f(tid, int(size(buf), size_t), ierr)
        if (.not. bad(ierr, 'string size', stat, errmsg)) then
            call h5tset_strpad_f(tid, H5T_STR_NULLPAD_F, ierr)
            if (.not. bad(ierr, 'string padding', stat, errmsg)) then
                call set_attr_raw(self, path, name, tid, none, c_loc(buf), stat, errmsg)
            end if
        end if
        if (ierr < 0) self%failed = .true.
        call release(tid)
    end subroutine sa_s

    !> Set a real scalar attribute.
    subroutine sa_r0(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! object path ('/' = file)
        character(len=*), intent(in) :: name                  !! attribute name
        real(wp), intent(in), target :: value                 !! value
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(hsize_t) :: none(0)
        call set_attr_raw(self, path, name, t_real(), none, c_loc(value), stat, errmsg)
    end subroutine sa_r0

    !> Set an integer scalar attribute.
    subroutine sa_i0(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! object path ('/' = file)
        character(len=*), intent(in) :: name                  !! attribute name
        integer, intent(in), target :: value                  !! value
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(hsize_t) :: none(0)
        call set_attr_raw(self, path, name, H5T_NATIVE_INTEGER, none, c_loc(value), stat, &
                          errmsg)
    end subroutine sa_i0

    !> Set a real 1D attribute.
    subroutine sa_r1(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                 !! the file
        character(len=*), intent(in) :: path                    !! object path ('/' = file)
        character(len=*), intent(in) :: name                    !! attribute name
        real(wp), intent(in), target, contiguous :: value(:)    !! value
        integer, intent(out), optional :: stat                  !! status code
        character(len=*), intent(inout), optional :: errmsg     !! message on error
        call set_attr_raw(self, path, name, t_real(), int(shape(value), hsize_t), &
                          c_loc(value), stat, errmsg)
    end subroutine sa_r1

    !> Set an integer 1D attribute.
    subroutine sa_i1(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                 !! the file
        character(len=*), intent(in) :: path                    !! object path ('/' = file)
        character(len=*), intent(in) :: name                    !! attribute name
        integer, intent(in), target, contiguous :: value(:)     !! value
        integer, intent(out), optional :: stat                  !! status code
        character(len=*), intent(inout), optional :: errmsg     !! message on error
        call set_attr_raw(self, path, name, H5T_NATIVE_INTEGER, int(shape(value), hsize_t), &
                          c_loc(value), stat, errmsg)
    end subroutine sa_i1

    !> Get a string attribute (trailing NULs removed).
    subroutine ga_s(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                 !! the file
        character(len=*), intent(in) :: path                    !! object path ('/' = file)
        character(len=*), intent(in) :: name                    !! attribute name
        character(len=:), allocatable, intent(out) :: value     !! value
        integer, intent(out), optional :: stat                  !! status code
        character(len=*), intent(inout), optional :: errmsg     !! message on error
        character(kind=c_char), allocatable, target :: buf(:)
        integer(hid_t) :: oid, aid, ftid, tid
        integer(hsize_t) :: n
        integer(size_t) :: sz
        integer :: st, ierr, i, k
        character(len=512) :: msg
        msg = ''
        ftid = -1; tid = -1
        value = ''
        call open_attr(self, path, name, oid, aid, n, st, msg)
        ok: block
            if (st /= FSYM_SUCCESS) exit ok
            call h5aget_type_f(aid, ftid, ierr)
            if (bad(ierr, 'type of attribute '//trim(name), st, msg)) exit ok
            call h5tget_size_f(ftid, sz, ierr)
            if (bad(ierr, 'size of attribute '//trim(name), st, msg)) exit ok
            call h5tcopy_f(H5T_C_S1, tid, ierr)
            if (bad(ierr, 'string type', st, msg)) exit ok
            call h5tset_size_f(tid, sz, ierr)
            if (bad(ierr, 'string size', st, msg)) exit ok
            call h5tset_strpad_f(tid, H5T_STR_NULLPAD_F, ierr)
            if (bad(ierr, 'string padding', st, msg)) exit ok
            allocate (buf(sz * max(1_hsize_t, n)))
            buf = c_null_char
        end block ok
        if (allocated(buf)) then
            call read_attr_close(oid, aid, tid, c_loc(buf), name, st, msg)
        else
            call close_attr(oid, aid)
        end if
        call release(tid); call release(ftid)
        if (st == FSYM_SUCCESS) then
            k = size(buf)
            do while (k > 0)
                if (buf(k) /= c_null_char) exit
                k = k - 1
            end do
            deallocate (value)
            allocate (character(len=k) :: value)
            do i = 1, k
                value(i:i) = buf(i)
            end do
        end if
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine ga_s

    !> Get a real scalar attribute.
    subroutine ga_r0(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! object path ('/' = file)
        character(len=*), intent(in) :: name                  !! attribute name
        real(wp), intent(out), target :: value                !! value
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(hid_t) :: oid, aid
        integer(hsize_t) :: n
        integer :: st
        character(len=512) :: msg
        msg = ''
        value = 0.0_wp
        call open_attr(self, path, name, oid, aid, n, st, msg)
        if (st == FSYM_SUCCESS .and. n /= 1) then
            call fsym_report(FSYM_ERR_IO, 'attribute '//trim(name)//' not scalar', st, msg)
        end if
        call read_attr_close(oid, aid, t_real(), c_loc(value), name, st, msg)
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine ga_r0

    !> Get an integer scalar attribute.
    subroutine ga_i0(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self               !! the file
        character(len=*), intent(in) :: path                  !! object path ('/' = file)
        character(len=*), intent(in) :: name                  !! attribute name
        integer, intent(out), target :: value                 !! value
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer(hid_t) :: oid, aid
        integer(hsize_t) :: n
        integer :: st
        character(len=512) :: msg
        msg = ''
        value = 0
        call open_attr(self, path, name, oid, aid, n, st, msg)
        if (st == FSYM_SUCCESS .and. n /= 1) then
            call fsym_report(FSYM_ERR_IO, 'attribute '//trim(name)//' not scalar', st, msg)
        end if
        call read_attr_close(oid, aid, H5T_NATIVE_INTEGER, c_loc(value), name, st, msg)
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine ga_i0

    !> Get a real 1D attribute.
    subroutine ga_r1(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                    !! the file
        character(len=*), intent(in) :: path                       !! object path ('/' = file)
        character(len=*), intent(in) :: name                       !! attribute name
        real(wp), allocatable, target, intent(out) :: value(:)     !! value
        integer, intent(out), optional :: stat                     !! status code
        character(len=*), intent(inout), optional :: errmsg        !! message on error
        integer(hid_t) :: oid, aid
        integer(hsize_t) :: n
        integer :: st
        character(len=512) :: msg
        msg = ''
        call open_attr(self, path, name, oid, aid, n, st, msg)
        allocate (value(max(1_hsize_t, n)))
        call read_attr_close(oid, aid, t_real(), c_loc(value), name, st, msg)
        if (n == 0) value = value(1:0)
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine ga_r1

    !> Get an integer 1D attribute.
    subroutine ga_i1(self, path, name, value, stat, errmsg)
        class(h5_file_t), intent(inout) :: self                    !! the file
        character(len=*), intent(in) :: path                       !! object path ('/' = file)
        character(len=*), intent(in) :: name                       !! attribute name
        integer, allocatable, target, intent(out) :: value(:)      !! value
        integer, intent(out), optional :: stat                     !! status code
        character(len=*), intent(inout), optional :: errmsg        !! message on error
        integer(hid_t) :: oid, aid
        integer(hsize_t) :: n
        integer :: st
        character(len=512) :: msg
        msg = ''
        call open_attr(self, path, name, oid, aid, n, st, msg)
        allocate (value(max(1_hsize_t, n)))
        call read_attr_close(oid, aid, H5T_NATIVE_INTEGER, c_loc(value), name, st, msg)
        if (n == 0) value = value(1:0)
        call fsym_pass(st, trim(msg), stat, errmsg)
    end subroutine ga_i1

end module fsym_h5
